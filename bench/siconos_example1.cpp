// siconos_example1: peer benchmark. Example 1 (xdot = A x + B lambda, 0 <= C x + e ⊥ lambda >= 0)
// simulated with Siconos' Euler-Moreau time stepping; prints terminal error and cost vs step count.
//
// Timing covers model construction, simulation set-up and all steps: with Siconos these are one
// piece (initialisation happens lazily inside the first step), so this is the cost of one answer.
#include <SiconosKernel.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <exception>
#include <iostream>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

const double kPi = std::acos(-1.0);
const double kFinalTime = 11.0 * kPi / 12.0 + std::sqrt(3.0);
const double kContactTime = 5.0 * kPi / 12.0;
const double kExactFinal[2] = {-1.0, 0.0};

struct Outcome {
  double error = std::numeric_limits<double>::quiet_NaN();
  double switch_time_error = std::numeric_limits<double>::quiet_NaN();
  double cpu_s = std::numeric_limits<double>::infinity();
  double wall_s = std::numeric_limits<double>::infinity();
  bool ok = true;
};

double cpuSeconds() {
  timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

// Grid t_k = k T / N with t_N = T exactly (N * (T / N) can miss T by an ulp). Siconos reads
// t_{k+2} (vector::at) after every step, so two padding instants beyond T are appended; they
// exceed T and are therefore never scheduled.
TkVector makeGrid(int steps) {
  const double h = kFinalTime / steps;
  TkVector tk(steps + 3);
  for (int k = 0; k < steps; ++k) tk[k] = k * h;
  tk[steps] = kFinalTime;
  tk[steps + 1] = kFinalTime + h;
  tk[steps + 2] = kFinalTime + 2.0 * h;
  return tk;
}

// One simulation; fills error / switch_time_error. Throws on Siconos failures.
void simulate(double theta, int steps, Outcome* out) {
  SP::SiconosVector x0(new SiconosVector(2));
  x0->setValue(0, std::sqrt(2.0));
  x0->setValue(1, std::sqrt(2.0));
  SP::SimpleMatrix a(new SimpleMatrix(2, 2));
  a->setValue(0, 1, 1.0);
  a->setValue(1, 0, -1.0);
  SP::SimpleMatrix b(new SimpleMatrix(2, 1));
  b->setValue(1, 0, 1.0);
  SP::SimpleMatrix c(new SimpleMatrix(1, 2));
  c->setValue(0, 1, 1.0);
  SP::SiconosVector e(new SiconosVector(1, 1.0));

  SP::FirstOrderLinearTIDS ds(new FirstOrderLinearTIDS(x0, a));
  SP::FirstOrderLinearTIR relation(new FirstOrderLinearTIR(c, b));
  relation->setePtr(e);
  SP::NonSmoothLaw law(new ComplementarityConditionNSL(1));
  SP::Interaction inter(new Interaction(law, relation));

  SP::NonSmoothDynamicalSystem nsds(new NonSmoothDynamicalSystem(0.0, kFinalTime));
  nsds->insertDynamicalSystem(ds);
  nsds->link(inter, ds);

  SP::TimeDiscretisation td(new TimeDiscretisation(makeGrid(steps)));
  SP::TimeStepping sim(new TimeStepping(nsds, td));
  // The one-argument constructor leaves gamma unused, so B lambda is taken fully implicitly at
  // t_{k+1}; theta only weights A x (0.5: trapezoidal smooth part).
  SP::EulerMoreauOSI osi(new EulerMoreauOSI(theta));
  sim->associate(osi, ds);
  SP::LCP lcp(new LCP());  // Lemke
  sim->insertNonSmoothProblem(lcp);

  int taken = 0;
  double contact = std::numeric_limits<double>::quiet_NaN();
  while (sim->hasNextEvent()) {
    sim->computeOneStep();
    ++taken;
    if (std::isnan(contact) && inter->lambda(0)->getValue(0) > 0.0) contact = sim->nextTime();
    sim->nextStep();
  }
  if (taken != steps) {
    throw std::runtime_error("took " + std::to_string(taken) + " steps instead of " +
                             std::to_string(steps));
  }
  const SiconosVector& x = *ds->x();
  out->error = std::hypot(x.getValue(0) - kExactFinal[0], x.getValue(1) - kExactFinal[1]);
  out->switch_time_error = std::fabs(contact - kContactTime);
}

Outcome measure(double theta, int steps, int repeat) {
  Outcome best;
  for (int r = 0; r < repeat; ++r) {
    Outcome run;
    const double cpu0 = cpuSeconds();
    const auto wall0 = std::chrono::steady_clock::now();
    try {
      simulate(theta, steps, &run);
    } catch (const std::exception& ex) {
      std::cerr << "theta=" << theta << " steps=" << steps << ": " << ex.what() << "\n";
      run.ok = false;
    } catch (...) {  // Whatever else escapes Siconos still only fails this row.
      std::cerr << "theta=" << theta << " steps=" << steps << ": Siconos exception\n";
      run.ok = false;
    }
    const double cpu = cpuSeconds() - cpu0;
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    best.cpu_s = std::min(best.cpu_s, cpu);
    best.wall_s = std::min(best.wall_s, wall);
    if (!run.ok) {
      best.ok = false;
      break;
    }
    best.error = run.error;
    best.switch_time_error = run.switch_time_error;
  }
  return best;
}

std::map<std::string, std::string> parseOptions(int argc, char** argv) {
  std::map<std::string, std::string> options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const auto eq = arg.find('=');
    if (arg.rfind("--", 0) != 0 || eq == std::string::npos) {
      throw std::invalid_argument("expected --key=value, got '" + arg + "'");
    }
    options[arg.substr(2, eq - 2)] = arg.substr(eq + 1);
  }
  for (const auto& [key, value] : options) {
    if (key != "thetas" && key != "steps" && key != "repeat") {
      throw std::invalid_argument("unknown option --" + key);
    }
  }
  return options;
}

std::vector<double> parseList(const std::string& text) {
  std::vector<double> values;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ',')) values.push_back(std::stod(item));
  return values;
}

// 10 to 100000 with three points per decade (1, 2.2, 4.6 times a power of ten).
std::vector<double> defaultSteps() {
  std::vector<double> steps;
  for (int i = 0; i <= 12; ++i) steps.push_back(std::round(10.0 * std::pow(10.0, i / 3.0)));
  return steps;
}

std::string formatNumber(double value) {
  if (std::isnan(value)) return "nan";
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.6e", value);
  return buffer;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<double> thetas;
  std::vector<double> steps;
  int repeat = 0;
  try {
    const auto options = parseOptions(argc, argv);
    const auto get = [&options](const std::string& key, const std::string& fallback) {
      const auto it = options.find(key);
      return it == options.end() ? fallback : it->second;
    };
    thetas = parseList(get("thetas", "0.5,1"));
    steps = options.count("steps") ? parseList(options.at("steps")) : defaultSteps();
    repeat = std::stoi(get("repeat", "3"));
    // Siconos 4.4 aborts on a one-step grid (assertion in TimeStepping::initializeNewtonLoop).
    for (const double n : steps) {
      if (n < 2) throw std::invalid_argument("--steps values must be at least 2");
    }
    if (repeat < 1) throw std::invalid_argument("--repeat must be at least 1");
  } catch (const std::exception& ex) {
    std::cerr << ex.what() << "\nusage: siconos_example1 [--thetas=0.5,1] [--steps=10,22,...]"
              << " [--repeat=3]\n";
    return 2;
  }

  std::cout << "method,scheme,n_s,n_fe_total,h,error,switch_time_error,cpu_s,wall_s,status\n";
  for (const double theta : thetas) {
    std::ostringstream method;
    method << "siconos_theta" << theta;
    for (const double n : steps) {
      const int count = static_cast<int>(n);
      const Outcome outcome = measure(theta, count, repeat);
      std::cout << method.str() << ",euler_moreau,1," << count << ","
                << formatNumber(kFinalTime / count) << "," << formatNumber(outcome.error) << ","
                << formatNumber(outcome.switch_time_error) << "," << formatNumber(outcome.cpu_s)
                << "," << formatNumber(outcome.wall_s) << "," << (outcome.ok ? "ok" : "failed")
                << std::endl;
    }
  }
  return 0;
}
