#pragma once
// Scratch files and folders a process makes beside the user's data or in
// the temp folder (the streamed cluster build's triangle files, a scan's
// page file until the scene is saved), and the sweep of those a crashed or
// killed process left behind.
//
// A name says which machine and process made it:
// <prefix><host>-<pid>-<serial><suffix>. The sweep removes only this
// machine's whose process is gone: a folder shared by render nodes holds
// other machines' live files, whose process ids mean nothing here.
#include <cstddef>
#include <filesystem>
#include <string>

namespace hs {

// A new name, unique in this process and (with the host and pid) beyond it.
std::string scratchName(const std::string& prefix, const std::string& suffix = "");

// Removes every entry of `dir` named by scratchName with `prefix` on this
// machine whose process no longer runs (files and folders with all they
// hold); returns how many. A missing or unreadable folder sweeps nothing.
size_t sweepStaleScratch(const std::filesystem::path& dir, const std::string& prefix);

}  // namespace hs
