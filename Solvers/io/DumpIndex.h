// The index of a LAMMPS dump (LammpsDump.h): each snapshot's header (ITEM: TIMESTEP, TIME,
// NUMBER OF ATOMS, BOX BOUNDS, ATOMS lines) and where its atom lines end, found by counting
// newlines rather than parsing rows. The row parser reads headers and skips lines with these.
#pragma once

#include "io/DumpText.h"
#include "io/LammpsDump.h"

#include <cstddef>
#include <string>
#include <vector>

namespace craterkit {
namespace dump {

// Reads the header of one snapshot (cursor at its first line); returns the entry and leaves
// the cursor after the ATOMS line. Fills frame if given.
DumpIndexEntry readDumpHeader(Cursor& c, ParticleFrame* frame, std::vector<std::string>* columns);

// The number of '\n' in [p, e).
std::size_t countNewlines(const char* p, const char* e);

struct NewlineCensus;
// Moves the cursor past n lines (fast: no parsing); a census of the cursor's text skips whole
// blocks at a time. A text with fewer lines fails naming the snapshot's first line.
void skipLines(Cursor& c, std::size_t n, std::size_t firstLine,
               const NewlineCensus* census = nullptr);

} // namespace dump
} // namespace craterkit
