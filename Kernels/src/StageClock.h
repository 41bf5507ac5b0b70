// Stage times of a frame on the host's clock: the CPU driver's, and the device driver's on
// Thrust's host system (on CUDA the device's clock times the stages, DeviceRuntime.h).
#pragma once

#include <chrono>

namespace iga
{
namespace sst
{

class StageClock
{
public:
  /// Starts the first stage.
  void begin() { this->Last = std::chrono::steady_clock::now(); }

  /// Ends a stage, adding its milliseconds to `ms`, and starts the next.
  void end(double& ms)
  {
    const auto now = std::chrono::steady_clock::now();
    ms += std::chrono::duration<double, std::milli>(now - this->Last).count();
    this->Last = now;
  }

  /// Nothing to wait for: the times are added as the stages end.
  void finish() {}

private:
  std::chrono::steady_clock::time_point Last;
};

} // namespace sst
} // namespace iga
