#pragma once
// Our PLY reader (Assimp's read a real tristrip scan as one triangle, with
// no word, and reads coordinates as float). ASCII and binary, either byte
// order; any property order and scalar type; positions read as double
// (UTM coordinates keep their digits: subtracted from a provisional origin
// before they become floats, as in the OBJ reader); normals; vertex UVs
// (u,v / s,t / texture_u,texture_v / texture_s,texture_t) or MeshLab's and
// Metashape's per-face `texcoord` lists (vertices split where a corner's UV
// differs), `texnumber` choosing among the `comment TextureFile` textures;
// faces as polygon lists (fans, counted) and `tristrips` elements (-1
// restarts, alternating winding); other elements skipped by their sizes.
// Vertex colours are read and not kept (meshes have no colour channel
// yet): the report says so.
//
// Every fault names the file, the element and its byte offset: header
// counts that exceed the file (refused before allocating), lists running
// past the end, truncated data, indices out of range (the face is dropped,
// counted and warned about, as in the OBJ reader).
#include <string>

#include "core/progress.h"
#include "mesh/byte_source.h"
#include "mesh/mesh_data.h"
#include "mesh/mesh_import.h"

namespace hs::mesh {

bool readPly(const ByteSource& source, const std::string& baseDir, const ImportOptions& options,
             const Progress* progress, MeshData& out, ImportReport& report, std::string& error);

}  // namespace hs::mesh
