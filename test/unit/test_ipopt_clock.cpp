// Ipopt's clock replaced (solver/ipopt_clock.cpp): the dynamic linker resolves libipopt's calls
// to Ipopt::CpuTime and Ipopt::SysTime to ours, which read no clock.
#include <dlfcn.h>

#include <gtest/gtest.h>

#include <coin/IpUtils.hpp>

namespace {

TEST(IpoptClock, LibipoptCallsOurs) {
  using Clock = double (*)();
  void* ipopt = dlopen("libipopt.so.1", RTLD_NOW | RTLD_NOLOAD);
  ASSERT_NE(ipopt, nullptr) << "libipopt is linked into the test";
  for (const char* name : {"_ZN5Ipopt7CpuTimeEv", "_ZN5Ipopt7SysTimeEv"}) {
    // What a call from libipopt through its PLT finds first (the global scope) ...
    const auto resolved = reinterpret_cast<Clock>(dlsym(RTLD_DEFAULT, name));
    // ... and libipopt's own definition.
    const auto own = reinterpret_cast<Clock>(dlsym(ipopt, name));
    ASSERT_NE(resolved, nullptr);
    ASSERT_NE(own, nullptr);
    EXPECT_NE(resolved, own) << name;
    EXPECT_EQ(resolved(), 0.0) << name;
  }
  // Ipopt's own clock measures this process' CPU time, which is not zero by now.
  const auto own_cpu = reinterpret_cast<Clock>(dlsym(ipopt, "_ZN5Ipopt7CpuTimeEv"));
  EXPECT_GT(own_cpu(), 0.0);
  dlclose(ipopt);
}

}  // namespace
