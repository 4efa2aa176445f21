// The IMM picture's steps of the registry's IMM mode set 2 (imm_picture_steps_of_set.hpp).
#define SKYFUSE_IMM_SET 2
#include "imm_picture_steps_of_set.hpp"
