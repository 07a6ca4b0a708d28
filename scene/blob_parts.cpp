#include "scene/blob_parts.h"

namespace hs::scene {

BlobRead readBlobParts(SqliteStmt& q, const std::string& key, std::vector<uint8_t>& bytes, std::string& sqlError) {
  int64_t expected = 0;
  q.bind(1, key);
  while (q.step(sqlError)) {
    if (q.integer(0) != expected++) {
      q.reset();
      return BlobRead::PartMissing;
    }
    const auto b = q.blob(1);
    bytes.insert(bytes.end(), b.begin(), b.end());
  }
  q.reset();
  if (!sqlError.empty()) return BlobRead::Failed;
  return expected == 0 ? BlobRead::Missing : BlobRead::Ok;
}

std::string blobReadProblem(BlobRead result, const std::string& sqlError) {
  switch (result) {
    case BlobRead::Ok: return "";
    case BlobRead::Missing: return "its data is missing from the file";
    case BlobRead::PartMissing: return "a part of its data is missing (damaged file)";
    case BlobRead::Failed: return "the scene file is damaged (" + sqlError + ")";
  }
  return "";
}

}  // namespace hs::scene
