#pragma once
/// \file
/// Every increment rule's contribution, defined (increment_rules.hpp declares them): for code
/// that runs a rule with sensors no configuration group compiles, the pictures' and the tests'.
/// One line per rule.

#include "skyfuse/tracking/ekf_increment_rule_impl.hpp"
#include "skyfuse/tracking/unscented_increment_rule_impl.hpp"
