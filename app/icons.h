#pragma once
// Icons drawn with QPainter at start-up: the build needs no image files and
// they stay crisp at any size or device pixel ratio.
#include <QIcon>

namespace hs::app {

enum class Icon {
  Select, Move, Rotate, Scale, World, Local, Snap, Frame, Grid,
  Mesh, Camera, Sun, PointLight, Empty, Group, Import
};

QIcon icon(Icon which);

}  // namespace hs::app
