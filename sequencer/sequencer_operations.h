#pragma once
// The timeline operations the editor and `hybridscape-cli` share, declared
// once (core/params.h): `sequence` (rate and range), `key`, `path`, and
// `farm verify`. `render` and `farm slurm` also take the scene's
// anti-aliasing and are scene/render_operation.h's.
#include "core/params.h"

namespace hs::sequencer {

// `sequence`: shows the timeline; --fps and --range change it.
const OperationDecl& sequenceOperation();
// `key`: one key on the timeline.
const OperationDecl& keyOperation();
// `path`: a camera path, its aim, banking and timing.
const OperationDecl& pathOperation();
// `farm verify`: checks the frames of a finished run.
const OperationDecl& farmVerifyOperation();

}  // namespace hs::sequencer
