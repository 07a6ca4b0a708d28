#include "sequencer/sequencer_operations.h"

#include "sequencer/camera_path.h"
#include "sequencer/export_loop.h"
#include "sequencer/frame_range.h"
#include "sequencer/keys.h"

namespace hs::sequencer {
namespace {

ParamDecl flag(const char* key, const char* option, const char* label, const char* help) {
  return {.key = key, .option = option, .label = label, .type = ParamType::Flag, .help = help};
}

ParamDecl text(const char* key, const char* option, const char* label, const char* help, const char* valueName) {
  return {.key = key, .option = option, .label = label, .type = ParamType::Text, .help = help, .valueName = valueName};
}

ParamDecl exportParam(const char* key) {
  ParamDecl p = paramIn(exportParamDecls(), key);
  p.group.clear();
  return p;
}

}  // namespace

const OperationDecl& sequenceOperation() {
  static const OperationDecl op = [] {
    ParamDecl range = frameNumberDecl();
    range.key = "range";
    range.option = "range";
    range.label = "Range";
    range.help = "the inclusive frame range render and the timeline use, FIRST <= LAST (e.g. 0-35999)";
    range.valueName = "FIRST-LAST";
    range.count = 2;
    range.separator = '-';
    range.oneForAll = true;  // "7" is the one frame 7
    range.ordered = true;
    range.editor = true;
    ParamDecl fps = exportParam("fps");
    fps.help = "60, 59.94, 60000/1001, 24 ... (keys stay at their times in seconds)";
    return OperationDecl{
        .name = "sequence",
        .summary = "show or set the timeline's frame rate and range",
        .usage = "<scene.hscene> [--fps RATE] [--range FIRST-LAST]",
        .description = "Shows the scene's timeline: frame rate, playback/export range and the animated entities with "
                       "their tracks. With options, changes them (undoable edits, as in the editor's timeline) and "
                       "saves.",
        .positionals = {{.name = "scene.hscene", .help = "the scene file"}},
        .params = {fps, range}};
  }();
  return op;
}

const OperationDecl& keyOperation() {
  static const OperationDecl op = [] {
    std::vector<std::string> names;
    for (auto i : {Interpolation::Constant, Interpolation::Linear, Interpolation::Cubic})
      names.push_back(interpolationName(i));
    return OperationDecl{
        .name = "key",
        .summary = "set a key on the timeline (an entity, material or settings field at a time)",
        .usage = "<entity> <property> <time> <value> <scene.hscene> [--interp I]\n"
                 "       hybridscape-cli key --material <material> <field> <time> <value> <scene.hscene> [--interp I]\n"
                 "       hybridscape-cli key --settings <field> <time> <value> <scene.hscene> [--interp I]",
        .description =
            "Sets a key on the timeline (an undoable edit, as the editor's key buttons make), then saves. A key "
            "already at that time gets the new value. <entity> is a name or an id; <time> is seconds (2.5) or a "
            "frame at the scene's rate (150f); <property> is an animatable field (see `hybridscape-cli set "
            "--help`): numbers, vectors x,y,z, colours, true/false for entity.visible; transform.rotation_deg takes "
            "Euler degrees and keys the rotation as a quaternion (turns take the short way). With --material, "
            "the key goes on a numeric or colour field of the material of that name (as `material list` prints "
            "it: roughness, opacity, emission_strength, ...), and there is no <entity>; with --settings, on a "
            "numeric or colour field of the scene settings (exposure_ev100, fog_density, ao_strength, ... as "
            "`set --help` lists them). An emitter's particles.rate_per_s and particles.wind_m_per_s are keyed into "
            "its own rate_keys and wind_keys (linear between keys, no --interp); its spawn values (particles.size_m, "
            "particles.speed_m_per_s, ...) are keyed as timeline tracks. Values outside a field's range are refused.",
        .notes = "Examples:\n"
                 "  key \"Main Camera\" camera.fov_deg 0 50 scene.hscene\n"
                 "  key \"Main Camera\" camera.fov_deg 120f 30 scene.hscene --interp linear\n"
                 "  key Bunny transform.translation 2.5 1,0,0 scene.hscene\n"
                 "  key Bunny transform.rotation_deg 5 0,0,90 scene.hscene\n"
                 "  key --material \"Bunny / default\" roughness 2 0.3 scene.hscene\n"
                 "  key --settings fog_density 10 0.002 scene.hscene\n"
                 "  key Snow particles.rate_per_s 20 4000 scene.hscene",
        .positionals = {{.name = "entity", .help = "a name or an id (not with --material or --settings)"},
                        {.name = "property", .help = "an animatable field"},
                        {.name = "time", .help = "seconds (2.5) or a frame (150f)"},
                        {.name = "value", .help = "the key's value"},
                        {.name = "scene.hscene", .help = "the scene file"}},
        .params = {{.key = "interp", .option = "interp", .label = "Interpolation", .type = ParamType::Choice,
                    .defaultValue = "cubic", .choices = names,
                    .help = "how the value moves to the next key (cubic: clamped auto tangents)", .valueName = "I"},
                   text("material", "material", "Material",
                        "key a field of this material (its name, as `material list` prints it) instead of an entity's",
                        "NAME"),
                   flag("settings", "settings", "Settings", "key a field of the scene settings instead of an entity's")}};
  }();
  return op;
}

const OperationDecl& pathOperation() {
  static const OperationDecl op = [] {
    OperationDecl o{
        .name = "path",
        .summary = "make a camera follow a path at constant speed (look-at or banking), edit or clear it",
        .usage = "<entity> <scene.hscene> [options]",
        .description =
            "Makes a camera (or any entity) follow a path at constant speed, changes the path or removes it, then "
            "saves: one undoable edit, as the editor's path tools make. The path is a smooth curve (natural cubic "
            "spline) through the points, travelled by arc length, so the speed is constant between the start and "
            "end times. It drives the entity's location and rotation (location and rotation keys it had are "
            "removed). Without options, shows the path. <entity> is a name or an id.",
        .notes = "Examples:\n"
                 "  path \"Main Camera\" valley.hscene --points \"0,-20,3;10,0,4;0,20,5\" --look-at 0,0,1\n"
                 "  path \"Main Camera\" valley.hscene --points \"0,-20,3;10,0,4;0,20,5\" --bank 25 --start 0 --end "
                 "600f\n"
                 "  path \"Main Camera\" valley.hscene --look-at-entity Bunny\n"
                 "  path \"Main Camera\" valley.hscene --clear",
        .positionals = {{.name = "entity", .help = "a name or an id"},
                        {.name = "scene.hscene", .help = "the scene file"}}};
    const std::vector<ParamDecl>& follow = pathFollowParamDecls();
    o.params = {
        text("points", "points", "Points",
             "the points in world metres, two or more (quote the ';'); a new path, or new points for the path the "
             "entity has",
             "\"X,Y,Z;X,Y,Z;...\""),
        paramIn(follow, "look_at_m"),
        text("look_at_entity", "look-at-entity", "Entity",
             "aim at an entity (a name or an id), following it as it moves", "NAME"),
        flag("look_along", "look-along", "Along the path", "aim along the direction of travel (a new path's default)"),
        paramIn(follow, "bank_deg"),
        paramIn(follow, "bank_scale"),
        text("start", "start", "Start", "cover the path at constant speed from this time: seconds (2.5) or a frame "
             "(150f); a new path's default is the sequence's range", "T"),
        text("end", "end", "End", "... to this time", "T"),
        flag("ease", "ease", "Ease", "with the times: start and stop softly (ease in and out)"),
        flag("clear", "clear", "Remove path", "stop following the path (the entity keeps its own transform)"),
    };
    return o;
  }();
  return op;
}

const OperationDecl& farmVerifyOperation() {
  static const OperationDecl op = [] {
    ParamDecl frames = exportParam("frames");
    frames.help = "the frames the run should have written, e.g. 0-35999";
    frames.required = true;
    ParamDecl out = text("out", "out", "Output", "the frame files, e.g. frames/f_%05d.png", "PATTERN");
    out.required = true;
    ParamDecl chunk{.key = "chunk", .option = "chunk", .label = "Chunk", .min = 0, .max = 100000000, .integer = true,
                    .defaultValue = 0, .help = "the farm's chunk size: name the chunks to run again (0: do not)",
                    .valueName = "N"};
    OperationDecl o{
        .name = "farm verify",
        .summary = "check a finished run",
        .usage = "--frames LIST --out PATTERN [--size WxH] [--layout L] [options]",
        .description = "Checks that every frame of the list exists and is a whole, valid image of the layout's size (the "
                       "check a farm run ends with). Exit 0 when all are there; 1 with the missing and invalid "
                       "frames listed (and, with --chunk, the array tasks to run again).",
        .params = {frames,
                   out,
                   exportParam("size_px"),
                   exportParam("layout"),
                   chunk,
                   flag("deep", "deep", "Deep",
                        "also decode every pixel (the default checks that each file is whole by its structure: "
                        "chunks, CRCs, end markers, offset tables; slower)"),
                   text("tag", "tag", "Job tag", "also require the export's job tag in each file", "TAG"),
                   {.key = "threads", .option = "threads", .label = "Threads", .min = 1, .max = 256, .integer = true,
                    .defaultValue = 2, .help = "files checked in parallel", .valueName = "N"}}};
    for (ParamDecl& p : o.params) p.editor = false;  // the editor verifies no farm runs
    return o;
  }();
  return op;
}

}  // namespace hs::sequencer
