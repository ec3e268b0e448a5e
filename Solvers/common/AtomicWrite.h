// Write-then-rename: every file CraterKit writes (checkpoints, particle files) goes through
// writeFileAtomically, so that a crash, a full disk or an abort never leaves a half-written
// file under the final name; the previous file, if any, stays until the new one is complete.
#pragma once

#include <functional>
#include <iosfwd>
#include <string>

namespace craterkit {

// Calls write(out) on a stream open on PATH + ".part", flushes it and renames it to PATH.
// Throws InputError when the file cannot be opened, std::runtime_error when the write or the
// rename fails; WHAT names the kind of file in the messages ("the DEM checkpoint").
void writeFileAtomically(const std::string& path, const std::string& what,
                         const std::function<void(std::ostream&)>& write);

} // namespace craterkit
