// Routes every CPU allocation the SDK makes through the host's obscura_allocator (or malloc/free),
// so an engine with its own memory tracking sees all of it. Containers inside the SDK use these aliases.
#ifndef OBSCURA_HOST_ALLOCATOR_H
#define OBSCURA_HOST_ALLOCATOR_H

#include <cstdlib>
#include <new>
#include <string>
#include <type_traits>
#include <vector>

#include "obscura/obscura.h"

namespace obscura {

// The resolved allocator callbacks; never null functions.
struct AllocatorCallbacks {
    void* (*alloc)(size_t size, void* user_data) = nullptr;
    void (*free)(void* ptr, void* user_data) = nullptr;
    void* user_data = nullptr;

    static AllocatorCallbacks from(const obscura_allocator& host) {
        if (!(host.alloc && host.free)) return system();
        AllocatorCallbacks callbacks;
        callbacks.alloc = host.alloc;
        callbacks.free = host.free;
        callbacks.user_data = host.user_data;
        return callbacks;
    }
    // malloc/free: what a context without a host allocator uses, and what code outside a context (the unit tests
    // of the layouts) builds with.
    static const AllocatorCallbacks& system() {
        static const AllocatorCallbacks callbacks = [] {
            AllocatorCallbacks c;
            c.alloc = [](size_t size, void*) { return std::malloc(size); };
            c.free = [](void* ptr, void*) { std::free(ptr); };
            return c;
        }();
        return callbacks;
    }
    void* allocate(size_t size) const { return alloc(size, user_data); }
    void release(void* ptr) const { if (ptr) free(ptr, user_data); }
};

// Stateful standard allocator that forwards to AllocatorCallbacks (which must outlive it). Containers take their
// allocator along when moved, copied or swapped into another (the propagate traits): a structure default-constructed
// as a member (its containers then on the system allocator, holding nothing) and later assigned a value built with
// the context's allocator keeps that allocator.
template <class T>
class HostAllocator {
public:
    using value_type = T;
    using propagate_on_container_move_assignment = std::true_type;
    using propagate_on_container_copy_assignment = std::true_type;
    using propagate_on_container_swap = std::true_type;
    HostAllocator() noexcept : callbacks_(&AllocatorCallbacks::system()) {}
    explicit HostAllocator(const AllocatorCallbacks* callbacks) noexcept : callbacks_(callbacks) {}
    template <class U>
    HostAllocator(const HostAllocator<U>& other) noexcept : callbacks_(other.callbacks()) {}

    T* allocate(size_t n) {
        if (n > size_t(-1) / sizeof(T)) throw std::bad_alloc();
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
