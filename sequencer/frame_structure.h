#pragma once
// A cheap check that a frame file is whole, without decoding its pixels:
// resume and `farm verify` run it on every frame, so it must cost a read of
// the file and no more. A frame cut short (a copy that stopped, a full disk
// on a file server, a file truncated by hand) opens fine in OpenImageIO,
// whose header parse says nothing about the end of the file.
#include <string>

namespace hs::sequencer {

// Empty when the file's structure is whole, else why not (without the path):
// PNG: every chunk lies within the file, its CRC matches and IEND is there;
// JPEG: starts with SOI and ends with the EOI marker. Other types (EXR,
// TIFF) are not checked here: their whole-file check is a decode
// (checkFrameFile does it), since their end is not marked.
std::string frameStructureProblem(const std::string& path);

// Whether frameStructureProblem() checks this file type (by extension), so
// that checkFrameFile decodes the others.
bool hasStructureCheck(const std::string& path);

}  // namespace hs::sequencer
