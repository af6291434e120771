// Ipopt 3.11.9 times every step of every iteration (IpTimedTask) with Ipopt::CpuTime and
// Ipopt::SysTime, each a getrusage(RUSAGE_SELF): a system call that sums the CPU time of every
// thread of the process. It took 12 % of the showcase's solve (perf), more in the node, whose
// other threads it walks, and it counted other requests' time as this solve's. A thread's own
// CPU clock is a system call too (about 300 per Ipopt iteration, 8 % of the solve). Ipopt has no
// option to turn its timing off before 3.12, and libipopt calls both through its PLT, so the
// definitions below take their place: Ipopt's CPU and system times are not measured (zero;
// they only feed its printed statistics and max_cpu_time, which we do not use). Solves are
// timed by our own clocks.
#include <coin/IpUtils.hpp>

namespace Ipopt {

Number CpuTime() {
  return 0.0;
}

Number SysTime() {
  return 0.0;
}

}  // namespace Ipopt
