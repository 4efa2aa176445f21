// The IMM picture's steps of the registry's IMM mode set 1 (imm_picture_steps_of_set.hpp).
#define SKYFUSE_IMM_SET 1
#include "imm_picture_steps_of_set.hpp"
