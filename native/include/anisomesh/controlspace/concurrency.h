#pragma once
// Which control spaces the parallel stages may query from several threads at once.
#include "anisomesh/controlspace/control_space.h"

namespace anisomesh {

// cs.concurrentQueries(): true for the adaptive structures (quadtree, background mesh),
// whose queries change no state outside their refine(), and for views over them that add
// no shared state (a parameterized space, a surface run's counting view, a minimum of such
// spaces); false for everything else (a CachedControlSpace mutates on every query, an
// analytic function may not be reentrant), which is then queried on one thread.
bool queriesAreConcurrent(const ControlSpace& cs);

}  // namespace anisomesh
