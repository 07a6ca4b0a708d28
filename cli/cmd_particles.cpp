// hybridscape-cli particles: emitters from presets, through the operation
// the editor's Particles panel uses (scene/particle_ops.h; declared once in
// particles/particle_operations.h). An emitter's fields are then set with
// `set EMITTER particles.FIELD VALUE` (cmd_set.cpp), and `info --time T`
// lists the live particles.
#include <cstdio>

#include "cli/commands.h"
#include "cli/subcommands.h"
#include "cli/terrain_cli.h"
#include "particles/particle_operations.h"
#include "scene/hscene_file.h"
#include "scene/particle_ops.h"
#include "scene/particle_world.h"

namespace hs::cli {
namespace {

int runAdd(int argc, char** argv) {
  const OperationDecl& op = particles::particlesAddOperation();
  OperationArgs args(op);
  if (auto code = args.parse(argc, argv)) return *code;
  if (args.positionals().size() != 2) return args.usage("expected a preset and a scene file");
  const std::string preset = args.positionals()[0], path = args.positionals()[1];
  Json values = Json::object();
  for (const ParamDecl& p : op.params)
    if (args.has(p.key)) values[p.key] = args.value(p.key);
  std::string error;
  scene::Document doc;
  if (!terrain_cli::openScene(path, doc, error)) return args.fail(error);
  const scene::EntityId id =
      scene::ops::addParticles(doc, preset, particles::presetFromValues(values), args.has("at"), error);
  if (id == scene::kNoEntity) return args.fail(error);
  const scene::Entity& top = *doc.state().find(id);
  std::vector<scene::EntityId> emitters = top.particles ? std::vector<scene::EntityId>{id} : top.children;
  for (scene::EntityId e : emitters) {
    const auto d = scene::emitterInWorld(doc.state(), e);
    std::printf("emitter \"%s\" (entity %llu): %s, %s, at %.3f, %.3f, %.3f, rate %g per s\n", d->name.c_str(),
                static_cast<unsigned long long>(e), particles::shapeName(d->shape), particles::spriteName(d->sprite),
                d->origin.x, d->origin.y, d->origin.z, d->rate);
  }
  if (!scene::saveScene(doc.state(), path, error)) return args.fail(error);
  std::printf("saved %s\n", path.c_str());
  return 0;
}

const Subcommand kSubs[] = {{"add", particles::particlesAddOperation, runAdd}};

}  // namespace

int runParticles(int argc, char** argv) {
  return runSubcommands("particles",
                        "Particle emitters of a scene (snow, fog, torch, campfire, dust), through the same\n"
                        "operation as the editor's Particles panel. The scene file is saved afterwards.\n"
                        "Fields: hybridscape-cli set EMITTER particles.FIELD VALUE SCENE (set --help lists them).\n",
                        kSubs, argc, argv);
}

}  // namespace hs::cli
