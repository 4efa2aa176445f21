// The code of a picture that its state size alone decides (picture/state_size_code.hpp),
// compiled for one of the build's state sizes: the one at SKYFUSE_STATE_SIZE_SLOT in
// picture_state_sizes(), nothing where the build has fewer sizes. core/CMakeLists.txt compiles
// this file once per slot (SKYFUSE_STATE_SIZE_SLOTS of them; none in a build of one shard,
// whose pictures' shard compiles every size).
#include "skyfuse/picture/state_size_code.hpp"

#include <cstddef>

namespace skyfuse {

static_assert(picture_state_sizes().count <= SKYFUSE_STATE_SIZE_SLOTS,
              "the pictures have more state sizes than slots: raise SKYFUSE_STATE_SIZE_SLOTS");

template void keep_state_size_slot<SKYFUSE_STATE_SIZE_SLOT>();

}  // namespace skyfuse
