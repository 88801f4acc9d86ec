// Routes every CPU allocation the SDK makes through the host's obscura_allocator (or malloc/free),
// so an engine with its own memory tracking sees all of it. Containers inside the SDK use these aliases.
#ifndef OBSCURA_HOST_ALLOCATOR_H
#define OBSCURA_HOST_ALLOCATOR_H

#include <cstdlib>
#include <new>
#include <string>
#include <vector>

#include "obscura/obscura.h"

namespace obscura {

// The resolved allocator callbacks; never null functions.
struct AllocatorCallbacks {
    void* (*alloc)(size_t size, void* user_data) = nullptr;
    void (*free)(void* ptr, void* user_data) = nullptr;
    void* user_data = nullptr;

    static AllocatorCallbacks from(const obscura_allocator& host) {
        AllocatorCallbacks callbacks;
        if (host.alloc && host.free) {
            callbacks.alloc = host.alloc;
            callbacks.free = host.free;
            callbacks.user_data = host.user_data;
        } else {
            callbacks.alloc = [](size_t size, void*) { return std::malloc(size); };
            callbacks.free = [](void* ptr, void*) { std::free(ptr); };
        }
        return callbacks;
    }
    void* allocate(size_t size) const { return alloc(size, user_data); }
    void release(void* ptr) const { if (ptr) free(ptr, user_data); }
};

// Stateful standard allocator that forwards to AllocatorCallbacks (which must outlive it).
template <class T>
class HostAllocator {
public:
    using value_type = T;
    explicit HostAllocator(const AllocatorCallbacks* callbacks) noexcept : callbacks_(callbacks) {}
    template <class U>
    HostAllocator(const HostAllocator<U>& other) noexcept : callbacks_(other.callbacks()) {}

    T* allocate(size_t n) {
        void* p = callbacks_->allocate(n * sizeof(T));
        if (!p) throw std::bad_alloc();
        return static_cast<T*>(p);
    }
    void deallocate(T* p, size_t) noexcept { callbacks_->release(p); }
    const AllocatorCallbacks* callbacks() const noexcept { return callbacks_; }

    template <class U>
    bool operator==(const HostAllocator<U>& other) const noexcept { return callbacks_ == other.callbacks(); }
    template <class U>
    bool operator!=(const HostAllocator<U>& other) const noexcept { return callbacks_ != other.callbacks(); }

private:
    const AllocatorCallbacks* callbacks_;
};

using HostString = std::basic_string<char, std::char_traits<char>, HostAllocator<char>>;
template <class T>
using HostVector = std::vector<T, HostAllocator<T>>;

}  // namespace obscura

#endif  // OBSCURA_HOST_ALLOCATOR_H
