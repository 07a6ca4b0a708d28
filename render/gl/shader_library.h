#pragma once
// GLSL programs from the embedded sources in shaders/, with `#include` and
// `#define` variants, built once and kept (ProgramDesc is the cache key).
//
// One source, several programs: lighting code exists once
// (shaders/lighting.glsl) and every shader that lights includes it; a
// variant is the same files with other defines ("SHADING_GOURAUD",
// "HAS_NORMAL_MAP", "MAX_LIGHTS 64"), so a feature costs nothing in
// programs that leave it out.
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "render/gl_program.h"

namespace hs::render::gl {

struct ProgramDesc {
  std::string vertex;    // file names under shaders/ ("mesh.vert"), or
  std::string fragment;  // empty for a compute program
  std::string compute;
  std::vector<std::string> defines;  // "NAME" or "NAME VALUE"
  // GLSL made at run time (OpenColorIO's LUT function, render/color_lut.h),
  // put into the fragment (or compute) stage after the defines; part of the key.
  std::string generated{};

  std::string key() const;
  std::string name() const;  // for messages: "mesh.vert + mesh.frag [SHADING_GOURAUD]"
};

// The text of `file` with its #includes expanded (each file once), the
// defines inserted after the #version line and #line directives that keep
// compiler messages pointing at the right file and line: GLSL names a
// source by number, so `files` receives the file of each number.
// False with `error` for a missing file or an include cycle.
// `generated` (ProgramDesc::generated) follows the defines as source
// "<generated>".
bool preprocessShader(std::string_view file, const std::vector<std::string>& defines, std::string& out,
                      std::vector<std::string>& files, std::string& error, std::string_view generated = {});

// The text of an include file (frame_blocks.glsl) with its own includes
// expanded, for a program written outside shaders/ that must read the
// renderer's blocks exactly as its shaders do (tests' probes). The caller
// puts the #version line first.
bool expandShaderInclude(std::string_view file, std::string& out, std::string& error);

class ShaderLibrary {
 public:
  // The program for `desc`, built on its first use; nullptr with `error`
  // (the compiler's log with file names) if it does not build.
  GlProgram* get(const ProgramDesc& desc, std::string& error);
  // Builds every program in `descs` now (initialisation checks them all).
  bool prebuild(const std::vector<ProgramDesc>& descs, std::string& error);
  size_t programCount() const { return programs_.size(); }
  // Every program built so far, in the order they were built (a variant
  // is its files and defines): what a frame made the library compile.
  const std::vector<ProgramDesc>& builtPrograms() const { return built_; }
  void release();

 private:
  std::map<std::string, std::unique_ptr<GlProgram>> programs_;
  std::vector<ProgramDesc> built_;
};

}  // namespace hs::render::gl
