#include "anisomesh/controlspace/concurrency.h"

namespace anisomesh {

bool queriesAreConcurrent(const ControlSpace& cs) { return cs.concurrentQueries(); }

}  // namespace anisomesh
