#pragma once
/// \file
/// Every filter part's increment rule: how a station turns its own measurement into the one
/// information increment it sends against the common prior, which every peer sums by the round
/// rule. A part names its rule (`IncrementRule`); the station, the center and the in-process
/// twin are generic over it (stations/single_model_fusion.hpp, fusion_center/central_fusion.hpp,
/// core/src/sim/increment_run_stepper.hpp). One line per rule.

#include "skyfuse/tracking/ekf_increment_rule.hpp"
#include "skyfuse/tracking/unscented_increment_rule.hpp"
