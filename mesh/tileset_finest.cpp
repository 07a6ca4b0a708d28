#include "mesh/tileset_finest.h"

namespace hs::mesh {

FinestContents finestContents(const Tileset& tree, const std::vector<TilesetContentRef>& contents) {
  FinestContents f;
  const size_t n = tree.tiles.size();
  std::vector<uint8_t> content(n, 0), below(n, 0), whole(n, 0), out(n, 0);
  std::vector<std::string> names(n);
  for (const TilesetContentRef& c : contents)
    if (c.tile >= 0 && size_t(c.tile) < n) {
      content[size_t(c.tile)] = 1;
      names[size_t(c.tile)] += (names[size_t(c.tile)].empty() ? "" : ", ") + c.file;
    }
  // Parents come before their children: one pass up marks what has content below.
  for (size_t i = n; i-- > 0;)
    if (tree.tiles[i].parent >= 0 && (content[i] || below[i])) below[size_t(tree.tiles[i].parent)] = 1;
  for (size_t i = 0; i < n; ++i) {
    if (!tree.tiles[i].contentMissing || content[i] || below[i]) continue;
    int p = tree.tiles[i].parent;
    while (p >= 0 && !content[size_t(p)]) p = tree.tiles[size_t(p)].parent;
    if (p < 0 || whole[size_t(p)]) continue;
    whole[size_t(p)] = 1;
    ++f.tilesKeptWhole;
    f.warnings.push_back(names[size_t(p)] + ": kept at its own level everywhere (the tiles under it are left out): " +
                         (tree.tiles[i].content.empty() ? std::string("a child tile") : "child " + tree.tiles[i].content) +
                         "'s content did not come in");
  }
  for (size_t i = 0; i < n; ++i) {
    const int p = tree.tiles[i].parent;
    out[i] = p >= 0 && (out[size_t(p)] || whole[size_t(p)]);
  }
  for (size_t r = 0; r < contents.size(); ++r) {
    const int t = contents[r].tile;
    if (t < 0 || size_t(t) >= n) continue;
    const size_t i = size_t(t);
    if (!out[i] && (whole[i] || tree.tiles[i].additive || !below[i])) f.refs.push_back(r);
    else ++f.contentsLeftOut;
  }
  return f;
}

}  // namespace hs::mesh
