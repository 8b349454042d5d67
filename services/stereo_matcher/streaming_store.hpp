// Writing the large per-frame volumes (costs, vertical paths) with
// non-temporal stores: a plain store to a line that is not cached first reads
// it from memory (read-for-ownership), which made the vertical paths spend
// most of their time waiting on stores. Streaming stores skip that read and
// leave the caches to the rows that are worked on.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <memory>

#if defined(__SSE__)
#include <xmmintrin.h>
#endif

namespace nerv::stereo {

// Makes streamed data visible to other threads (before they read the volume). On x86 the
// path steps stream with AVX2 or, without it, SSE (simd_bytes.hpp), so any x86 build fences;
// NEON has no non-temporal store (its "stream" is a plain store, which the threads' own
// synchronisation orders).
inline void streamingFence() {
#if defined(__SSE__)
  _mm_sfence();
#endif
}

// A byte buffer aligned to 64 bytes (cache line), reallocated only on growth.
class AlignedBytes {
 public:
  uint8_t* data() { return data_.get(); }
  const uint8_t* data() const { return data_.get(); }
  size_t size() const { return size_; }
  void resize(size_t n) {
    if (n <= capacity_) {
      size_ = n;
      return;
    }
    void* p = std::aligned_alloc(64, (n + 63) / 64 * 64);
    if (!p) throw std::bad_alloc();
    data_.reset(static_cast<uint8_t*>(p));
    size_ = capacity_ = n;
  }

 private:
  struct Free {
    void operator()(uint8_t* p) const { std::free(p); }
  };
  std::unique_ptr<uint8_t, Free> data_;
  size_t size_ = 0, capacity_ = 0;
};

}  // namespace nerv::stereo
