#pragma once
// An allocator that keeps freed large blocks for reuse by the same thread (docs/performance.md,
// "Measurements"). The Voronoi measurement builds a fresh CGAL triangulation on every
// call; CGAL's Compact_container allocates its cells and vertices in blocks whose sizes follow
// the same sequence every time, and freeing them returns the memory to the system, so each
// call paid page faults on fresh memory (~40 % of its time). voronoi.cpp makes this CGAL's
// allocator (CGAL_ALLOCATOR); blocks of at least kMinBytes are kept in a per-thread pool keyed
// by size (at most kMaxKeptBytes in all), smaller ones go to operator new / delete directly.
#include <cstddef>
#include <new>
#include <unordered_map>
#include <vector>

namespace invasim {

// Freed blocks of one thread, by size in bytes; released when the thread ends.
class BlockPool {
 public:
  static constexpr std::size_t kMinBytes = 4096;
  static constexpr std::size_t kMaxKeptBytes = std::size_t(256) << 20;

  BlockPool() = default;
  BlockPool(const BlockPool&) = delete;
  BlockPool& operator=(const BlockPool&) = delete;
  ~BlockPool() {
    for (auto& [bytes, blocks] : free_)
      for (void* p : blocks) ::operator delete(p);
    gone() = true;
  }

  // The calling thread's pool; nullptr once it has been destroyed (thread or program exit:
  // blocks freed then go straight back to operator delete).
  static BlockPool* of_this_thread() {
    if (gone()) return nullptr;
    thread_local BlockPool pool;
    return &pool;
  }

  void* take(std::size_t bytes) {
    if (bytes >= kMinBytes) {
      const auto it = free_.find(bytes);
      if (it != free_.end() && !it->second.empty()) {
        void* p = it->second.back();
        it->second.pop_back();
        kept_ -= bytes;
        return p;
      }
    }
    return ::operator new(bytes);
  }

  void give(void* p, std::size_t bytes) noexcept {
    if (bytes >= kMinBytes && kept_ + bytes <= kMaxKeptBytes) {
      try {
        free_[bytes].push_back(p);
        kept_ += bytes;
        return;
      } catch (...) {  // no memory for the bookkeeping: release the block instead
      }
    }
    ::operator delete(p);
  }

  std::size_t kept_bytes() const { return kept_; }

 private:
  static bool& gone() {
    thread_local bool flag = false;  // trivially destructible: still readable at exit
    return flag;
  }
  std::unordered_map<std::size_t, std::vector<void*>> free_;
  std::size_t kept_ = 0;
};

// Standard allocator on top of the calling thread's BlockPool (stateless: all instances are
// interchangeable, a block may be freed by another thread than the one that allocated it).
template <class T>
struct RecyclingAllocator {
  using value_type = T;
  RecyclingAllocator() noexcept = default;
  template <class U>
  RecyclingAllocator(const RecyclingAllocator<U>&) noexcept {}
  T* allocate(std::size_t n) {
    static_assert(alignof(T) <= __STDCPP_DEFAULT_NEW_ALIGNMENT__, "over-aligned type");
    if (n > std::size_t(-1) / sizeof(T)) throw std::bad_array_new_length();
    BlockPool* pool = BlockPool::of_this_thread();
    return static_cast<T*>(pool ? pool->take(n * sizeof(T)) : ::operator new(n * sizeof(T)));
  }
  void deallocate(T* p, std::size_t n) noexcept {
    if (BlockPool* pool = BlockPool::of_this_thread())
      pool->give(p, n * sizeof(T));
    else
      ::operator delete(p);
  }
  template <class U>
  bool operator==(const RecyclingAllocator<U>&) const noexcept {
    return true;
  }
};

}  // namespace invasim
