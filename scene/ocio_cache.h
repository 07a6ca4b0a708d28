#pragma once
// What the LUT (color_lut.h) and the config (ocio_config.h) share in
// handing the document's colour data to OpenColorIO 2.1, which reads only
// files: a per-user cache folder, files written there atomically, and
// OpenColorIO's messages turned into ones that name what the user knows.
#include <filesystem>
#include <string>

namespace hs::scene {

// <temp>/<name>-<uid>: one per user, shared by that user's processes.
std::filesystem::path userCacheFolder(const std::string& name);

// Writes `bytes` to `file` (and its folders) under a name of its own
// (core/scratch_files.h: `<file>.part-<host>-<pid>-<n>`), then renames it,
// so render nodes sharing a temporary folder never read half a file; a file
// already there with that size is left (its name is its content's hash).
// First removes the parts of `file` that dead processes of this machine
// left. False with `error` naming the file.
bool writeCacheFile(const std::filesystem::path& file, const std::string& bytes, std::string& error);

// OpenColorIO's `message` with the cache path `cachePath` replaced by
// `name` (what the user imported), its lines joined into one.
std::string ocioMessage(std::string message, const std::string& cachePath, const std::string& name);

}  // namespace hs::scene
