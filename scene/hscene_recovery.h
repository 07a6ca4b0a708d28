#pragma once
// Opening a scene after a crash. A save killed part-way (power cut, kill -9)
// leaves the .hscene beside a "hot" rollback journal holding the pages it had
// begun to overwrite. SQLite plays such a journal back on the first
// read-write open, which restores the last saved state exactly; a read-only
// open cannot, and fails with "attempt to write a readonly database". So
// before a scene is read or saved, the journal is played back here and the
// user is told what happened, instead of the file being called damaged.
#include <string>

namespace hs::scene {

enum class JournalRecovery {
  None,        // no journal beside the file, or another program is mid-save (not hot)
  RolledBack,  // an interrupted save was undone: the last saved state is intact
  StrayRemoved,  // a file named like a journal but not one SQLite wrote; SQLite discarded it
  Failed,      // there is a hot journal that could not be played back; `message` says why
};

// Plays back a hot journal beside `path`. `message` is set for every
// outcome but None: a line for the user naming the file.
JournalRecovery recoverInterruptedSave(const std::string& path, std::string& message);

}  // namespace hs::scene
