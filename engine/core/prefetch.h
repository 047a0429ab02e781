// Software prefetch: asks the memory system for a cache line that a loop will read or write
// a few iterations later. The pair loops read their partners' data at addresses the
// processor cannot guess (a fibre-fibre bond's or a contact's partner lies anywhere in the
// particle arrays), and on a sheet whose arrays are far larger than the cache each of those
// reads waits on memory (docs/performance.md, "Prefetching the partners").
//
// Every helper that prefetches is forced inline, here and where loops group them: GCC
// judges a function whose only effect is a prefetch to have no effect at all and drops the
// calls to it, as it silently did to the bond walk's first version.
#pragma once

namespace fibrenet {

// The cache line holding `address`, for reading.
[[gnu::always_inline]] inline void PrefetchForRead(const void* address) {
  __builtin_prefetch(address, 0);
}

// The cache line holding `address`, for writing.
[[gnu::always_inline]] inline void PrefetchForWrite(const void* address) {
  __builtin_prefetch(address, 1);
}

// Every cache line of the object at `address`: a Quat (32 bytes) or a BondState (96 bytes)
// may straddle two or three lines.
template <class T>
[[gnu::always_inline]] inline void PrefetchObjectForRead(const T* address) {
  const char* first = reinterpret_cast<const char*>(address);
  for (unsigned offset = 0; offset < sizeof(T); offset += 64) PrefetchForRead(first + offset);
  PrefetchForRead(first + sizeof(T) - 1);
}

}  // namespace fibrenet
