#pragma once
// Which control spaces the parallel stages may query from several threads at once.
#include "anisomesh/controlspace/control_space.h"

namespace anisomesh {

// True for the adaptive structures (quadtree, background mesh), whose queries change no
// state outside their refine(); false for everything else (a CachedControlSpace mutates on
// every query, an analytic function may not be reentrant), which is then queried on one thread.
bool queriesAreConcurrent(const ControlSpace& cs);

}  // namespace anisomesh
