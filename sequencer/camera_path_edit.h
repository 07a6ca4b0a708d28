#pragma once
// Edits of a camera path value, shared by the editor's path tools, the CLI's
// `path` command and tests: the progress keys that cover a path at constant
// speed over a time range, a new path from points, where an inserted point
// goes, and the checks a path passes before it enters a document. Pure
// functions on plain data (scene/camera_path_edits.h wraps them in undoable
// edits).
#include <optional>
#include <string>
#include <vector>

#include "sequencer/camera_path.h"

namespace hs::sequencer {

// A new path is this far ahead of a camera that starts it (metres), when
// nothing else says how long it should be.
inline constexpr double kDefaultPathLength = 10.0;

// Progress keys 0 at t0 and 1 at t1, linear: the path is covered at constant
// speed over [t0, t1] and the camera holds at its ends outside. `ease` on the
// first key (Ease::InOut) starts and stops softly over the same range.
ScalarTrack constantSpeedProgress(double t0, double t1, Ease ease = Ease::None);

// A path through `points`, covered at constant speed over [t0, t1], aiming
// along the direction of travel, no banking.
PathFollow makePathFollow(std::vector<glm::dvec3> points, double t0, double t1);

// Where "insert a point after point `index`" puts it: on the curve halfway
// (in the spline's chord-length parameter) to the next point, so the shape
// barely changes; after the last point, beyond it along the direction of
// travel by the last span's length.
glm::dvec3 pointAfter(const CameraPath& path, size_t index);

// Why the path cannot be followed, or nullopt: fewer than two distinct
// points, a coordinate or key that is not finite, a banking limit outside
// (0, 90] degrees or a banking strength that is not positive. Entity targets
// are the scene's to check (scene::pathProblem).
std::optional<std::string> pathProblem(const PathFollow& follow);

}  // namespace hs::sequencer
