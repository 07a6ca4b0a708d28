#include "scene/sqlite_db.h"

#include <sqlite3.h>

namespace hs::scene {

SqliteDb::~SqliteDb() { close(); }

bool SqliteDb::open(const std::string& path, bool readOnly, bool create, std::string& error) {
  close();
  int flags = readOnly ? SQLITE_OPEN_READONLY : SQLITE_OPEN_READWRITE;
  if (create && !readOnly) flags |= SQLITE_OPEN_CREATE;
  flags |= SQLITE_OPEN_NOMUTEX;
  if (sqlite3_open_v2(path.c_str(), &db_, flags, nullptr) != SQLITE_OK) {
    error = db_ ? sqlite3_errmsg(db_) : "out of memory";
    close();
    return false;
  }
  sqlite3_extended_result_codes(db_, 1);
  // Never map the file: a mapped database that shrinks under us (another
  // program cutting it) would be SIGBUS, where a read is an error. Debian
  // builds SQLite with mapping off; this holds with any build.
  sqlite3_exec(db_, "PRAGMA mmap_size=0", nullptr, nullptr, nullptr);
  sqlite3_busy_timeout(db_, 5000);  // another process (CLI) may be writing
  return true;
}

void SqliteDb::close() {
  if (db_) sqlite3_close_v2(db_);
  db_ = nullptr;
}

bool SqliteDb::exec(const std::string& sql, std::string& error) {
  char* msg = nullptr;
  if (sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &msg) != SQLITE_OK) {
    error = msg ? msg : lastError();
    sqlite3_free(msg);
    return false;
  }
  return true;
}

std::string SqliteDb::lastError() const { return db_ ? sqlite3_errmsg(db_) : "no database"; }

SqliteStmt::SqliteStmt(SqliteDb& db, const std::string& sql) : db_(db) {
  if (sqlite3_prepare_v2(db.handle(), sql.c_str(), int(sql.size()), &stmt_, nullptr) != SQLITE_OK) {
    stmt_ = nullptr;
    prepareError_ = db.lastError();
  }
}

SqliteStmt::~SqliteStmt() {
  if (stmt_) sqlite3_finalize(stmt_);
}

// A statement that did not prepare (a table missing from a damaged file)
// stays inert: binds and reads do nothing, step() reports SQLite's error.
// SQLite's own functions dereference a null statement.
void SqliteStmt::bind(int index, std::string_view text) {
  if (!stmt_) return;
  sqlite3_bind_text(stmt_, index, text.data(), int(text.size()), SQLITE_TRANSIENT);
}
void SqliteStmt::bind(int index, int64_t value) {
  if (stmt_) sqlite3_bind_int64(stmt_, index, value);
}
void SqliteStmt::bindBlob(int index, std::span<const uint8_t> bytes) {
  if (!stmt_) return;
  // Static: the caller keeps the bytes alive until step(); no copy of a 256 MB part.
  sqlite3_bind_blob64(stmt_, index, bytes.data(), bytes.size(), SQLITE_STATIC);
}

bool SqliteStmt::step(std::string& error) {
  if (!stmt_) {
    error = prepareError_;
    return false;
  }
  const int rc = sqlite3_step(stmt_);
  if (rc == SQLITE_ROW) return true;
  if (rc != SQLITE_DONE) error = db_.lastError();
  return false;
}

void SqliteStmt::reset() {
  if (!stmt_) return;
  sqlite3_reset(stmt_);
  sqlite3_clear_bindings(stmt_);
}

std::string SqliteStmt::text(int column) const {
  if (!stmt_) return {};
  const auto* t = sqlite3_column_text(stmt_, column);
  return t ? std::string(reinterpret_cast<const char*>(t), size_t(sqlite3_column_bytes(stmt_, column))) : std::string();
}
int64_t SqliteStmt::integer(int column) const { return stmt_ ? sqlite3_column_int64(stmt_, column) : 0; }
std::span<const uint8_t> SqliteStmt::blob(int column) const {
  if (!stmt_) return {};
  const auto* p = static_cast<const uint8_t*>(sqlite3_column_blob(stmt_, column));
  return {p, size_t(sqlite3_column_bytes(stmt_, column))};
}

}  // namespace hs::scene
