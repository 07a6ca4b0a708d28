#include "render/gl/shader_library.h"

#include <algorithm>
#include <set>

namespace hs::render::gl {
namespace {

// Appends `file` (already known to exist) to `out`, expanding includes.
bool expand(std::string_view file, std::string& out, std::vector<std::string>& files, std::set<std::string>& done,
            std::vector<std::string>& stack, std::string& error) {
  const std::string name(file);
  if (std::find(stack.begin(), stack.end(), name) != stack.end()) {
    error = "shaders/" + name + ": included from itself (an include cycle)";
    return false;
  }
  if (done.count(name)) return true;  // each file once, like #pragma once
  done.insert(name);
  const std::string_view src = embeddedShader(file);
  if (src.empty()) {
    error = "shader source shaders/" + name + " is not in this build";
    return false;
  }
  stack.push_back(name);
  const size_t index = files.size();
  files.push_back(name);
  size_t line = 1, pos = 0;
  out += "#line 1 " + std::to_string(index) + "\n";
  while (pos < src.size()) {
    const size_t eol = std::min(src.find('\n', pos), src.size());
    const std::string_view text = src.substr(pos, eol - pos);
    const size_t first = text.find_first_not_of(" \t");
    const std::string_view trimmed = first == std::string_view::npos ? std::string_view() : text.substr(first);
    if (trimmed.rfind("#version", 0) == 0) {
      // Only the top file's #version counts; it was written first.
      out += "\n";
    } else if (trimmed.rfind("#include", 0) == 0) {
      const size_t q0 = trimmed.find('"'), q1 = q0 == std::string_view::npos ? q0 : trimmed.find('"', q0 + 1);
      if (q1 == std::string_view::npos) {
        error = "shaders/" + name + ":" + std::to_string(line) + ": #include needs a \"file\"";
        return false;
      }
      if (!expand(trimmed.substr(q0 + 1, q1 - q0 - 1), out, files, done, stack, error)) return false;
      out += "#line " + std::to_string(line + 1) + " " + std::to_string(index) + "\n";
    } else {
      out.append(text);
      out += "\n";
    }
    pos = eol + 1;
    ++line;
  }
  stack.pop_back();
  return true;
}

}  // namespace

std::string ProgramDesc::key() const {
  std::string k = vertex + "|" + fragment + "|" + compute;
  std::vector<std::string> d = defines;
  std::sort(d.begin(), d.end());
  for (const auto& x : d) k += "|" + x;
  if (!generated.empty()) k += "|generated:" + generated;
  return k;
}

std::string ProgramDesc::name() const {
  std::string n = compute.empty() ? vertex + " + " + fragment : compute;
  if (!defines.empty()) {
    n += " [";
    for (size_t i = 0; i < defines.size(); ++i) n += (i ? ", " : "") + defines[i];
    n += "]";
  }
  return n;
}

bool preprocessShader(std::string_view file, const std::vector<std::string>& defines, std::string& out,
                      std::vector<std::string>& files, std::string& error, std::string_view generated) {
  const std::string_view src = embeddedShader(file);
  if (src.empty()) {
    error = "shader source shaders/" + std::string(file) + " is not in this build";
    return false;
  }
  const size_t eol = src.find('\n');
  const std::string_view first = src.substr(0, eol);
  if (first.rfind("#version", 0) != 0) {
    error = "shaders/" + std::string(file) + ": the first line must be #version";
    return false;
  }
  out.assign(first);
  out += "\n";
  for (const auto& d : defines) out += "#define " + d + "\n";
  if (!generated.empty()) {
    out += "#line 1 " + std::to_string(files.size()) + "\n";
    files.push_back("<generated>");
    out.append(generated);
    out += "\n";
  }
  std::set<std::string> done;
  std::vector<std::string> stack;
  return expand(file, out, files, done, stack, error);
}

bool expandShaderInclude(std::string_view file, std::string& out, std::string& error) {
  std::vector<std::string> files;
  std::set<std::string> done;
  std::vector<std::string> stack;
  out.clear();
  return expand(file, out, files, done, stack, error);
}

GlProgram* ShaderLibrary::get(const ProgramDesc& desc, std::string& error) {
  const std::string key = desc.key();
  if (auto it = programs_.find(key); it != programs_.end()) return it->second.get();
  auto p = std::make_unique<GlProgram>();
  if (!p->build(desc, error)) return nullptr;
  built_.push_back(desc);
  return programs_.emplace(key, std::move(p)).first->second.get();
}

bool ShaderLibrary::prebuild(const std::vector<ProgramDesc>& descs, std::string& error) {
  for (const auto& d : descs)
    if (!get(d, error)) return false;
  return true;
}

void ShaderLibrary::release() {
  for (auto& [k, p] : programs_) p->release();
  programs_.clear();
  built_.clear();
}

}  // namespace hs::render::gl
