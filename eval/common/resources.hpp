// Process resources from Linux /proc: resident set size now (VmRSS) and its peak (VmHWM),
// and the machine's CPU model for reports. Absent (std::nullopt / "unknown") when /proc
// does not say.
#pragma once

#include <optional>
#include <string>

namespace lifelong::eval {

/// MB (2^20 bytes) resident now, from /proc/self/status VmRSS.
std::optional<double> CurrentRssMb();
/// MB (2^20 bytes) peak resident ("high water mark"), from /proc/self/status VmHWM.
std::optional<double> PeakRssMb();
/// Resets the peak (VmHWM) to the current RSS by writing 5 to /proc/self/clear_refs
/// (Linux >= 4.0), so that the next PeakRssMb() covers only what runs from now on.
/// Also hands freed heap memory back to the system first (malloc_trim). False when the
/// kernel does not allow it.
bool ResetPeakRss();
/// "model name" of the first CPU in /proc/cpuinfo and the number of CPUs listed, e.g.
/// "Intel(R) Xeon(R) ... (2 CPUs)"; "unknown" when not available.
std::string CpuModelName();

}  // namespace lifelong::eval
