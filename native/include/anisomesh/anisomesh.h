#pragma once
// Umbrella header: the whole public API of the anisomesh core.
#include "anisomesh/adapt/adaptation_loop.h"
#include "anisomesh/adapt/hessian_recovery.h"
#include "anisomesh/adapt/metric_from_hessian.h"
#include "anisomesh/adapt/solution_transfer.h"
#include "anisomesh/controlspace/control_space.h"
#include "anisomesh/controlspace/minimum_control_space.h"
#include "anisomesh/core/error.h"
#include "anisomesh/core/types.h"
#include "anisomesh/mesh/mesh.h"
#include "anisomesh/metric/metric.h"
