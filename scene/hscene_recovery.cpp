#include "scene/hscene_recovery.h"

#include <cstring>
#include <filesystem>
#include <fstream>

#include <sqlite3.h>

#include "scene/sqlite_db.h"

namespace hs::scene {
namespace {

// The first 8 bytes of every rollback journal SQLite writes (pager.c aJournalMagic).
constexpr unsigned char kJournalMagic[8] = {0xd9, 0xd5, 0x05, 0xf9, 0x20, 0xa1, 0x63, 0xd7};

bool nonEmptyFile(const std::string& path) {
  std::error_code ec;
  return std::filesystem::is_regular_file(path, ec) && std::filesystem::file_size(path, ec) > 0 && !ec;
}

bool hasJournalMagic(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  unsigned char head[8] = {};
  f.read(reinterpret_cast<char*>(head), sizeof head);
  return f.gcount() == 8 && std::memcmp(head, kJournalMagic, 8) == 0;
}

}  // namespace

JournalRecovery recoverInterruptedSave(const std::string& path, std::string& message) {
  message.clear();
  const std::string journal = path + "-journal";
  if (!nonEmptyFile(journal) || !nonEmptyFile(path)) return JournalRecovery::None;
  const bool real = hasJournalMagic(journal);
  const std::string keep = " Do not delete '" + journal +
                           "': it holds the only copy of the parts the interrupted save had begun to overwrite.";

  // Any statement makes the pager check for a hot journal and play it back
  // (under an exclusive lock, so another reader never sees it half done).
  SqliteDb db;
  std::string e;
  if (!db.open(path, false, false, e)) {
    message = path + ": an interrupted save left a journal beside it, and the file cannot be opened for writing to "
                     "restore its last saved state (" + e + ")." + keep;
    return JournalRecovery::Failed;
  }
  const bool readOnly = sqlite3_db_readonly(db.handle(), "main") == 1;
  if (!db.exec("SELECT count(*) FROM sqlite_master", e) || readOnly) {
    db.close();
    if (!nonEmptyFile(journal)) {  // another program finished it meanwhile
      message = path + ": recovered from an interrupted save; the last saved state is intact";
      return JournalRecovery::RolledBack;
    }
    if (readOnly)
      message = path + ": an interrupted save left a journal beside it, and the file is read-only, so its last saved "
                       "state cannot be restored here. Make the file and its folder writable (or copy both files to "
                       "a writable folder) and open it again." + keep;
    else
      message = path + ": an interrupted save left a journal beside it that could not be played back (" + e + ")." +
                keep;
    return JournalRecovery::Failed;
  }
  db.close();
  // Played back and removed; still there means it was not hot (another
  // process holds the file mid-save, and SQLite waited or left it alone).
  if (nonEmptyFile(journal)) return JournalRecovery::None;
  if (!real) {
    message = path + ": a file named like its journal ('" + journal +
              "') was not one SQLite wrote; it was discarded and the scene is unchanged";
    return JournalRecovery::StrayRemoved;
  }
  message = path + ": recovered from an interrupted save; the last saved state is intact";
  return JournalRecovery::RolledBack;
}

}  // namespace hs::scene
