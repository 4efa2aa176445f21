// The IMM picture's steps of the registry's IMM mode set 0 (imm_picture_steps_of_set.hpp).
#define SKYFUSE_IMM_SET 0
#include "imm_picture_steps_of_set.hpp"
