// Counts calls of one GL entry point by swapping libepoxy's dispatch pointer for a counting
// wrapper while alive. Resolve the entry point first (call it once): libepoxy's resolving stub
// rewrites the pointer, and would overwrite the wrapper.
#pragma once

#include <type_traits>

namespace penumbra::testing {

template <auto* Slot, typename Function = std::remove_pointer_t<decltype(Slot)>>
class CountedGlCalls;

template <auto* Slot, typename Result, typename... Arguments>
class CountedGlCalls<Slot, Result (*)(Arguments...)> {
 public:
  explicit CountedGlCalls(int& counter) {
    real_ = *Slot;
    counter_ = &counter;
    *Slot = &counted;
  }
  ~CountedGlCalls() { *Slot = real_; }
  CountedGlCalls(const CountedGlCalls&) = delete;
  CountedGlCalls& operator=(const CountedGlCalls&) = delete;

 private:
  static Result counted(Arguments... arguments) {
    ++*counter_;
    return real_(arguments...);
  }
  static inline Result (*real_)(Arguments...) = nullptr;
  static inline int* counter_ = nullptr;
};

}  // namespace penumbra::testing
