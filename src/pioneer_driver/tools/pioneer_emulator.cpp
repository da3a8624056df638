// pioneer_emulator: a Pioneer 3DX controller speaking ARCOS on a pseudo-terminal, so the driver and the
// whole stack run without the robot: `rosrun pioneer_driver pioneer_emulator --link /tmp/pioneer` then
// `roslaunch biovision_bringup robot.launch pioneer_port:=/tmp/pioneer`.
#include <chrono>
#include <csignal>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include "biovision_common/tool_options.hpp"
#include "pioneer_driver/arcos_emulator.hpp"

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
  biovision_common::ToolOptions options("pioneer_emulator",
                                        "A Pioneer 3DX (ARCOS) on a pseudo-terminal: handshake, VEL/RVEL, SIPs.");
  std::string link = "/tmp/biovision_pioneer";
  double sip_period = 0.1, duration = 0.0, status_period = 5.0;
  options.app().add_option("--link", link, "symlink to the pty slave that the driver opens");
  options.app().add_option("--sip-period", sip_period, "seconds between SIPs")->check(biovision_common::kPositive);
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
    pioneer_driver::ArcosEmulator emulator(link, sip_period);
    std::printf("pioneer_emulator: ARCOS on %s\n", emulator.port().c_str());
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
        const auto sp = emulator.setpoint();
        std::printf(
            "pioneer_emulator: session %s, motors %s, VEL %d mm/s, RVEL %d deg/s, pose (%.3f m, %.3f m, "
            "%.3f rad), %lu SIPs, %lu bad checksums\n",
            emulator.sessionOpen() ? "open" : "closed", emulator.motorsEnabled() ? "on" : "off", sp.vel_mm_s,
            sp.rvel_deg_s, emulator.x(), emulator.y(), emulator.yaw(), emulator.sipsSent(), emulator.badChecksums());
        std::fflush(stdout);
        next_status = now + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                std::chrono::duration<double>(status_period));
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "pioneer_emulator: %s\n", e.what());
    return 1;
  }
  return 0;
}
