// The framing every CraterKit checkpoint file shares (DEM .ckdem, SPH .cksph, bonded): a header
// that names the kind and the format version, the solver's payload, and CRC-32 checksums, so
// that a damaged file is refused before any of it is used.
//
// Format version 2 (written by every solver). Integers in the header are little-endian; the
// payload is what each solver's writer produces (native byte order, as before):
//
//   offset  bytes  field
//        0      8  magic "CRATERKT"
//        8      4  format version (uint32, 2)
//       12      4  header size (uint32, 72)
//       16      8  kind, ASCII padded with NULs: "DEM", "SPH" or "BONDED"
//       24     32  writer: the CraterKit version that wrote the file, ASCII padded with NULs
//       56      8  payload size in bytes (uint64)
//       64      4  CRC-32 of the payload (zlib's crc32, the polynomial of gzip and PNG)
//       68      4  CRC-32 of bytes 0-67 (the header itself)
//       72      -  payload: the kind's own layout (for DEM and SPH exactly the bytes of a
//                  version-1 file; the bonded one adds the shock heating at its end)
//
// Reading checks, in this order and before any byte of the payload is parsed: the magic, the
// version, the header's checksum, the kind, that the file holds exactly the payload size
// after the header (a file cut short, or with bytes after its end, is refused), and the
// payload's checksum. Any failure throws InputError; a checksum that does not match gives
// "<path>: the checkpoint is corrupt (checksum mismatch)" (the solver's reader adds the path).
// A CRC-32 detects every single-bit error, and a flipped bit of the magic or the version fails
// those checks, so a file with one bit flipped anywhere is refused (CheckpointFormatTest
// flips 100 bits of a real checkpoint of each kind).
//
// Version 1 (before the framing): the bare payload, which begins with its kind's own magic
// ("CKDEMCP1", "CKSPH1\n\0", "CKBOND01"). Such files still read, as before (the payload's own
// checks: sizes against the bytes left, a trailer for the DEM), with a warning naming the file
// that its integrity cannot be checked: in DemSolver::warnings(), BondedSolver::warnings(),
// SphRun::warnings() or readSphCheckpoint's `warning`; the filters (on a resume) and
// CraterKitCheckpointReader pass it to vtkWarningMacro. A run resumed from one writes version
// 2 at its next checkpoint. A run whose resume failed (a damaged file, another set-up) writes
// no checkpoint at all, so the file it could not read is never overwritten.
//
// The payload layouts are documented where they are written: dem/DemCheckpoint.h,
// sph/SphCheckpoint.h, bonded/BondedCheckpoint.h. Files are written through
// writeFileAtomically (common/AtomicWrite.h).
#pragma once

#include "craterkit/Version.h" // generated: CRATERKIT_VERSION

#include <cstdint>
#include <functional>
#include <iosfwd>
#include <string>

namespace craterkit {

// The CraterKit version written into every checkpoint's header: the project's VERSION in the
// top-level CMakeLists.txt, through the generated <craterkit/Version.h>.
inline constexpr const char* kCraterKitVersion = CRATERKIT_VERSION;

// The version written, and the size of its header.
inline constexpr std::uint32_t kCheckpointFormatVersion = 2;
inline constexpr std::uint64_t kCheckpointHeaderBytes = 72;

// What tells one kind of checkpoint from another.
struct CheckpointKind {
  const char* name;        // header kind and messages: "DEM", "SPH", "BONDED"
  const char* description; // in messages: "DEM checkpoint"
  char legacyMagic[8];     // the first 8 bytes of a version-1 file of this kind
};

// What the reader found in front of the payload.
struct CheckpointFrame {
  std::uint32_t version = 0; // 1: an old file without checksums; 2: checked
  std::string writer;        // the CraterKit version that wrote it (empty for version 1)
  std::uint64_t payloadBytes = 0;
  std::string warning; // non-empty for version 1 (no checksum), without the path
};

// Writes the header, the payload that `payload` writes to the stream it is given, and then
// fills in the header's size and checksums (OUT must be seekable: a file or a string stream;
// the checksum is computed as the payload streams through, so the payload is never held
// twice). Throws std::runtime_error if the stream fails.
void writeCheckpointFrame(std::ostream& out, const CheckpointKind& kind,
                          const std::function<void(std::ostream&)>& payload);

// The same into PATH, atomically (PATH.part renamed into place).
void writeCheckpointFile(const std::string& path, const CheckpointKind& kind,
                         const std::function<void(std::ostream&)>& payload);

// The same as bytes in memory, for the snapshots a run keeps (DemRun): the string is allocated
// once at its exact size, the payload being written twice (counted, then stored), so that a
// snapshot never holds a growing buffer and a copy of itself at once.
std::string checkpointBytes(const CheckpointKind& kind,
                            const std::function<void(std::ostream&)>& payload);

// Calls read(in, size) with IN reading BYTES where they are (no copy) and SIZE their count.
void readCheckpointBytes(const std::string& bytes,
                         const std::function<void(std::istream&, std::uint64_t)>& read);

// Checks the frame of the `available` bytes from IN's position (the whole payload's checksum
// included, read through once) and leaves IN at the payload's first byte: for version 1, at
// the position it had (the payload is the whole file). Throws InputError with a message
// without the path ("the checkpoint is corrupt (checksum mismatch)").
CheckpointFrame readCheckpointFrame(std::istream& in, std::uint64_t available,
                                    const CheckpointKind& kind);

// Opens PATH, checks its frame (readCheckpointFrame) and calls read(in, frame) with IN at the
// payload. An InputError, of the frame or thrown by read, gets "PATH: " in front, and so does
// frame.warning.
void readCheckpointFile(const std::string& path, const CheckpointKind& kind,
                        const std::function<void(std::istream&, const CheckpointFrame&)>& read);

// The standard CRC-32 (zlib's crc32) of `bytes` bytes, continuing from `crc` (0 to start).
std::uint32_t checkpointCrc32(const void* data, std::uint64_t bytes, std::uint32_t crc = 0);

} // namespace craterkit
