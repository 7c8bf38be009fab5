#include "anisomesh/controlspace/concurrency.h"

#include "anisomesh/controlspace/adaptive_control_space.h"

namespace anisomesh {

bool queriesAreConcurrent(const ControlSpace& cs) { return dynamic_cast<const AdaptiveControlSpace*>(&cs) != nullptr; }

}  // namespace anisomesh
