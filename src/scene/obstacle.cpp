// Obstacles as contract bodies: a box is a rectangle core, a circle a disc.
#include "earc/scene/scenario.hpp"

namespace earc {

geo::Body Obstacle::body() const {
  if (type == Type::Circle) return geo::Body::disc(center, radius);
  return geo::Body::box(center, size * 0.5, angle);
}

}  // namespace earc
