#pragma once
// A scene file opened behind the library's back with SQLite, as a user with
// the sqlite3 shell would: statements run on it, blobs read and replaced,
// keys counted. For the suites that damage files or check what a save wrote.
// The suite links SQLite::SQLite3.
#include <QtTest>

#include <cstdint>
#include <string>
#include <vector>

#include <sqlite3.h>

namespace hs::test {

// Runs `statement` on the file; fails the test if it cannot be opened or the
// statement fails (with SQLite's message).
inline void sql(const std::string& path, const std::string& statement) {
  sqlite3* db = nullptr;
  QVERIFY(sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READWRITE, nullptr) == SQLITE_OK);
  char* msg = nullptr;
  const int rc = sqlite3_exec(db, statement.c_str(), nullptr, nullptr, &msg);
  const std::string why = msg ? msg : "";
  sqlite3_free(msg);
  sqlite3_close(db);
  QVERIFY2(rc == SQLITE_OK, why.c_str());
}

// The bytes of the first part of blob `key`; empty if there is none.
inline std::vector<uint8_t> readBlob(const std::string& path, const std::string& key) {
  sqlite3* db = nullptr;
  std::vector<uint8_t> out;
  sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr);
  sqlite3_stmt* st = nullptr;
  sqlite3_prepare_v2(db, "SELECT data FROM blobs WHERE key = ?1 AND part = 0", -1, &st, nullptr);
  sqlite3_bind_text(st, 1, key.c_str(), -1, SQLITE_TRANSIENT);
  if (sqlite3_step(st) == SQLITE_ROW) {
    const auto* p = static_cast<const uint8_t*>(sqlite3_column_blob(st, 0));
    out.assign(p, p + sqlite3_column_bytes(st, 0));
  }
  sqlite3_finalize(st);
  sqlite3_close(db);
  return out;
}

// Replaces the first part of blob `key` with `bytes`.
inline void writeBlob(const std::string& path, const std::string& key, const std::vector<uint8_t>& bytes) {
  sqlite3* db = nullptr;
  sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READWRITE, nullptr);
  sqlite3_stmt* st = nullptr;
  sqlite3_prepare_v2(db, "UPDATE blobs SET data = ?2 WHERE key = ?1 AND part = 0", -1, &st, nullptr);
  sqlite3_bind_text(st, 1, key.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_blob(st, 2, bytes.data(), int(bytes.size()), SQLITE_TRANSIENT);
  QCOMPARE(sqlite3_step(st), SQLITE_DONE);
  sqlite3_finalize(st);
  sqlite3_close(db);
}

// The scene description's text (the document table's one row); empty if
// there is none.
inline std::string readDescription(const std::string& path) {
  sqlite3* db = nullptr;
  std::string out;
  sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr);
  sqlite3_stmt* st = nullptr;
  sqlite3_prepare_v2(db, "SELECT json FROM document WHERE id = 1", -1, &st, nullptr);
  if (sqlite3_step(st) == SQLITE_ROW)
    out.assign(reinterpret_cast<const char*>(sqlite3_column_text(st, 0)), size_t(sqlite3_column_bytes(st, 0)));
  sqlite3_finalize(st);
  sqlite3_close(db);
  return out;
}

// Replaces the scene description's text.
inline void writeDescription(const std::string& path, const std::string& text) {
  sqlite3* db = nullptr;
  QVERIFY(sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READWRITE, nullptr) == SQLITE_OK);
  sqlite3_stmt* st = nullptr;
  sqlite3_prepare_v2(db, "UPDATE document SET json = ?1 WHERE id = 1", -1, &st, nullptr);
  sqlite3_bind_text(st, 1, text.data(), int(text.size()), SQLITE_TRANSIENT);
  const int rc = sqlite3_step(st);
  sqlite3_finalize(st);
  sqlite3_close(db);
  QCOMPARE(rc, SQLITE_DONE);
}

// How many distinct blob keys satisfy `where` (an SQL condition on `key`);
// -1 if the file cannot be read.
inline int countBlobKeys(const std::string& path, const std::string& where) {
  sqlite3* db = nullptr;
  sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr);
  sqlite3_stmt* st = nullptr;
  const std::string query = "SELECT COUNT(DISTINCT key) FROM blobs WHERE " + where;
  sqlite3_prepare_v2(db, query.c_str(), -1, &st, nullptr);
  const int n = sqlite3_step(st) == SQLITE_ROW ? sqlite3_column_int(st, 0) : -1;
  sqlite3_finalize(st);
  sqlite3_close(db);
  return n;
}

}  // namespace hs::test
