// A test process that starts a process group and then waits to be killed, for the test that a
// crashed test leaves nothing behind (tests/integration/crash_cleanup_test.cpp).
// Usage: testkit_process_group_child <dds-domain> <pid-file>
// Starts mosquitto and slam-mapper, then writes "<name> <pid>" lines to <pid-file> (complete once
// the file exists) and sleeps until a signal ends it.
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>

#include "process_group.hpp"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s <dds-domain> <pid-file>\n", argv[0]);
    return 2;
  }
  try {
    slam::testkit::ProcessGroup group;
    group.start_mosquitto();
    group.start("mapper", {slam::testkit::bin_path("slam-mapper"), "--domain", argv[1], "--store",
                           group.dir() + "/store.db"});
    const std::string pid_file = argv[2];
    {
      std::ofstream out(pid_file + ".tmp");
      out << "mosquitto " << group.pid("mosquitto") << "\nmapper " << group.pid("mapper") << "\n";
    }
    std::filesystem::rename(pid_file + ".tmp", pid_file);
    while (true) ::pause();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
}
