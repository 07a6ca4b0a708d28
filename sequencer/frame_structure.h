#pragma once
// A cheap check that a frame file is whole, without decoding its pixels:
// resume and `farm verify` run it on every frame, so it must cost a read of
// the file and no more. A frame cut short (a copy that stopped, a full disk
// on a file server, a file truncated by hand) opens fine in OpenImageIO,
// whose header parse says nothing about the end of the file. Per 3840x1080
// noise frame (farm verify, one thread): 26-36 ms by structure against
// 164-290 ms decoded (docs/reliability.md).
#include <string>

namespace hs::sequencer {

// Empty when the file's structure is whole, else why not (without the path):
// PNG: every chunk lies within the file, its CRC matches and IEND is there;
// JPEG: starts with SOI and ends with the EOI marker; OpenEXR (single-part
// scanline): every chunk the offset table lists lies within the file; TIFF:
// every strip or tile of the first image lies within the file. `unknown` is
// set for what this walk does not cover (tiled or multi-part EXR, BigTIFF,
// other types): checkFrameFile decodes those.
std::string frameStructureProblem(const std::string& path, bool& unknown);

}  // namespace hs::sequencer
