// phantomx_emulator: two AX-12A servos (IDs 1 and 2) on a Dynamixel 1.0 bus behind a pseudo-terminal, so
// the head driver and the stack run without the turret: `rosrun phantomx_driver phantomx_emulator --link
// /tmp/biovision_phantomx` then `roslaunch biovision_bringup robot.launch phantomx_port:=/tmp/biovision_phantomx`.
#include <chrono>
#include <csignal>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include "biovision_common/tool_options.hpp"
#include "phantomx_driver/ax12_bus_emulator.hpp"

namespace
{
volatile std::sig_atomic_t g_stop = 0;
void onSignal(int)
{
  g_stop = 1;
}
}  // namespace

int main(int argc, char** argv)
{
  biovision_common::ToolOptions options("phantomx_emulator", "AX-12A pan/tilt servos (Dynamixel 1.0) on a pty.");
  std::string link = "/tmp/biovision_phantomx";
  int pan_id = 1, tilt_id = 2;
  double duration = 0.0, status_period = 5.0;
  options.app().add_option("--link", link, "symlink to the pty slave that the driver opens");
  options.app().add_option("--pan-id", pan_id, "pan servo ID")->check(CLI::Range(0, 253));
  options.app().add_option("--tilt-id", tilt_id, "tilt servo ID")->check(CLI::Range(0, 253));
  options.app()
      .add_option("--duration", duration, "seconds to run (0 = until SIGINT/SIGTERM)")
      ->check(biovision_common::kNonNegative);
  options.app()
      .add_option("--status-period", status_period, "seconds between status lines (0 = none)")
      ->check(biovision_common::kNonNegative);
  options.parse(argc, argv);  // skips roslaunch's __name:= and __log:=
  std::signal(SIGINT, onSignal);
  std::signal(SIGTERM, onSignal);
  try
  {
    const auto pan = static_cast<uint8_t>(pan_id), tilt = static_cast<uint8_t>(tilt_id);
    phantomx_driver::Ax12BusEmulator bus({pan, tilt}, link);
    std::printf("phantomx_emulator: AX-12 bus (IDs %d, %d) on %s\n", pan_id, tilt_id, bus.port().c_str());
    std::fflush(stdout);
    const auto start = std::chrono::steady_clock::now();
    auto next_status = start;
    while (!g_stop)
    {
      const auto now = std::chrono::steady_clock::now();
      if (duration > 0.0 && std::chrono::duration<double>(now - start).count() >= duration)
        break;
      if (status_period > 0.0 && now >= next_status)
      {
        std::printf(
            "phantomx_emulator: pan %.1f -> %d ticks (torque %s), tilt %.1f -> %d ticks (torque %s), %lu "
            "SYNC_WRITEs, %lu bad checksums\n",
            bus.position(pan), bus.goal(pan), bus.torqueOn(pan) ? "on" : "off", bus.position(tilt), bus.goal(tilt),
            bus.torqueOn(tilt) ? "on" : "off", bus.syncWrites(), bus.badChecksums());
        std::fflush(stdout);
        next_status = now + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                std::chrono::duration<double>(status_period));
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "phantomx_emulator: %s\n", e.what());
    return 1;
  }
  return 0;
}
