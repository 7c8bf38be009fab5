#pragma once
// Umbrella header: the whole public API of the anisomesh core.
#include "anisomesh/controlspace/control_space.h"
#include "anisomesh/controlspace/minimum_control_space.h"
#include "anisomesh/core/error.h"
#include "anisomesh/core/types.h"
#include "anisomesh/mesh/mesh.h"
#include "anisomesh/metric/metric.h"
