// The code of a picture that its state size alone decides (picture/state_size_code.hpp),
// compiled for one of the build's state sizes: the one at SKYFUSE_STATE_SIZE_SLOT in
// picture_state_sizes(), nothing where the build has fewer sizes. core/CMakeLists.txt compiles
// this file once per slot (SKYFUSE_STATE_SIZE_SLOTS of them).
#include "skyfuse/picture/state_size_code.hpp"

#include <cstddef>

#include "skyfuse/picture/picture_parts.hpp"

namespace skyfuse {
namespace {
constexpr PictureStateSizes kSizes = picture_state_sizes();
}  // namespace

static_assert(kSizes.count <= SKYFUSE_STATE_SIZE_SLOTS,
              "the pictures have more state sizes than slots: raise SKYFUSE_STATE_SIZE_SLOTS");

template <std::size_t Slot>
void keep_state_size_code() {
  if constexpr (Slot < kSizes.count) {
    StateSizeCode<kSizes.sizes[Slot]>::keep();
    if constexpr (kSizes.linearises[Slot]) StateSizeCode<kSizes.sizes[Slot]>::keep_linearisation();
  }
}

template void keep_state_size_code<SKYFUSE_STATE_SIZE_SLOT>();

}  // namespace skyfuse
