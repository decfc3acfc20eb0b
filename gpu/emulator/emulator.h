#pragma once
// A CUDA-subset emulator on the host: one Boost.Context fiber per CUDA thread, every fiber of a
// block on one OS thread (so shared memory is plain per-block storage), the blocks of a grid
// spread over oneTBB. It implements only what our kernels use and checks what a GPU would hang on
// or get silently wrong; every such finding is an EmulatorError out of the launch.
//
// Kernel code does not include this header directly: it includes "gpu/emulator/kernel.h", which
// maps the same source onto nvcc or onto this emulator.
#include <atomic>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <version>
#if __has_include(<source_location>)
#include <source_location>
#endif

namespace shadowcts::emu {

// Where a device-side call was written, for reports. std::source_location where the library
// has it; clang 14 with libstdc++ 12 (the fuzz build's pair) has not, but has the builtins.
class Location {
 public:
#if defined(__cpp_lib_source_location)
  static constexpr Location current(std::source_location where = std::source_location::current()) {
    return Location(where.file_name(), where.line(), where.column());
  }
#else
  static constexpr Location current(const char* file = __builtin_FILE(),
                                    unsigned line = __builtin_LINE(),
                                    unsigned column = __builtin_COLUMN()) {
    return Location(file, line, column);
  }
#endif
  constexpr Location() = default;
  constexpr const char* file_name() const {
    return file_;
  }
  constexpr unsigned line() const {
    return line_;
  }
  constexpr unsigned column() const {
    return column_;
  }

 private:
  constexpr Location(const char* file, unsigned line, unsigned column)
      : file_(file), line_(line), column_(column) {}
  const char* file_ = "";
  unsigned line_ = 0, column_ = 0;
};

struct Dim3 {
  unsigned x = 1, y = 1, z = 1;
  constexpr Dim3(unsigned x_ = 1, unsigned y_ = 1, unsigned z_ = 1) : x(x_), y(y_), z(z_) {}
};

struct Uint3 {
  unsigned x = 0, y = 0, z = 0;
};

inline constexpr int warp_size = 32;
// CUDA's default limit for static plus dynamic shared memory of one block (no opt-in here).
inline constexpr std::size_t max_shared_bytes = 48 * 1024;

enum class Schedule {
  run_until_block,  // each fiber runs until it blocks, then the next one in thread order
  random,           // seeded: a fiber may yield at every collective, atomic and shared access
};

struct Options {
  Schedule schedule = Schedule::run_until_block;
  std::uint64_t seed = 0;
  bool check_races = false;  // per-byte shared-memory race and uninitialized-read tracking
};

// The options launches on this OS thread use. Defaults come from the environment:
// SHADOWCTS_EMU_SCHEDULE=random:<seed> and SHADOWCTS_EMU_CHECK_RACES=1.
Options current_options();

// Sets the options for launches from this OS thread while it lives.
class ScopedOptions {
 public:
  explicit ScopedOptions(const Options& options);
  ~ScopedOptions();
  ScopedOptions(const ScopedOptions&) = delete;
  ScopedOptions& operator=(const ScopedOptions&) = delete;

 private:
  Options saved_;
};

enum class ErrorKind {
  invalid_launch,         // grid, block or shared size a GPU would refuse
  invalid_argument,       // a collective's mask without the caller, a bad shuffle width
  barrier_divergence,     // a block barrier not reached by every thread, or different barriers
  warp_lane_missing,      // a warp collective's mask names a lane that does not arrive
  warp_lane_exited,       // a warp collective's mask names a lane that has exited (or none)
  shuffle_inactive_lane,  // a shuffle reads a lane that takes no part in it
  shared_race,            // a shared access racing another thread's since the last barrier
  shared_uninitialized,   // a shared read of bytes nothing in the block has written
  shared_out_of_bounds,   // a shared index past its array
  deadlock,               // no thread can run and no more specific check explains why
  outside_kernel,         // a device-side call made outside a kernel
};

const char* to_string(ErrorKind kind);

class EmulatorError : public std::runtime_error {
 public:
  EmulatorError(ErrorKind kind, std::string kernel, Uint3 block, Uint3 thread, std::string file,
                unsigned line, const std::string& message);
  ErrorKind kind;
  std::string kernel;
  Uint3 block, thread;
  std::string file;
  unsigned line;
};

namespace detail {

struct ThreadInfo {
  Uint3 thread_idx, block_idx;
  Dim3 block_dim, grid_dim;
};

// The running CUDA thread; throws outside_kernel when there is none.
const ThreadInfo& this_thread();

enum class Barrier { plain, count, and_, or_ };
int block_barrier(Barrier kind, int predicate, const Location& where);

enum class Collective { syncwarp, shfl, shfl_up, shfl_down, shfl_xor, ballot, any, all };
std::uint64_t warp_collective(Collective kind, unsigned mask, std::uint64_t value, int lane_arg,
                              int width, const Location& where);
unsigned active_mask(const Location& where);

// A point where the random schedule may switch threads (atomics on global memory).
void yield_point();

// Static shared declarations: one object per declaration, placed on first use in each block.
struct SharedDecl {
  std::size_t size, align;
  const char* name;
};
std::size_t shared_static(const SharedDecl& decl, const Location& where);
std::size_t dynamic_shared_bytes();
std::byte* shared_base();

enum class Access { read, write, atomic };
// Yield point, then race/uninitialized tracking of bytes [offset, offset + size).
void shared_access(std::size_t offset, std::size_t size, Access access, const Location& where);
// The running block's shared arena while its accesses need neither tracking nor yield points
// (run-until-block schedule, race checks off), else null: then a load or store is a plain copy,
// not two calls into the emulator per access.
extern thread_local std::byte* untracked_shared_base;
[[noreturn]] void shared_out_of_bounds(std::size_t index, std::size_t extent,
                                       const Location& where);

using ThreadEntry = void (*)(const void* bound_kernel);
void launch(const char* kernel, Dim3 grid, Dim3 block, std::size_t dynamic_shared,
            const Location& where, ThreadEntry entry, const void* bound_kernel);

}  // namespace detail

// ---------------------------------------------------------------------------------------------
// Shared memory. A declared name is a SharedVar; indexing yields SharedRef proxies that are only
// usable as temporaries, so every read and write goes through the tracking. Elements are read and
// written whole (no member access, no raw pointers): code that needs more does not compile.

// An index that remembers where it was written, for error reports.
struct Index {
  template <typename I>
  requires std::is_integral_v<I> Index(I i,
                                       Location where = Location::current())  // NOLINT: implicit
      : value(static_cast<std::size_t>(i)), negative(std::cmp_less(i, 0)), loc(where) {}
  std::size_t value;
  bool negative;
  Location loc;
};

template <typename T>
class SharedPtr {
 public:
  SharedPtr(std::size_t offset, Location where) : offset_(offset), loc_(where) {}
  std::size_t offset() const { return offset_; }
  const Location& where() const { return loc_; }

 private:
  std::size_t offset_;
  Location loc_;
};

template <typename T>
class SharedRef;

namespace detail {
template <typename T>
inline constexpr bool shared_element_v = std::is_trivially_copyable_v<T> && !std::is_array_v<T>;

// A shared array has no value of its own: its reads and writes convert to this unusable type.
struct NotAnElement {
  NotAnElement() = delete;
};
template <typename T>
using element_t = std::conditional_t<std::is_array_v<T>, NotAnElement, T>;

template <typename T>
T shared_load(std::size_t offset, const Location& where) {
  std::byte* base = untracked_shared_base;
  if (base == nullptr) {
    shared_access(offset, sizeof(T), Access::read, where);
    base = shared_base();
  }
  T value;
  std::memcpy(&value, base + offset, sizeof(T));
  return value;
}
template <typename T>
void shared_store(std::size_t offset, const T& value, const Location& where) {
  std::byte* base = untracked_shared_base;
  if (base == nullptr) {
    shared_access(offset, sizeof(T), Access::write, where);
    base = shared_base();
  }
  std::memcpy(base + offset, &value, sizeof(T));
}

// Operations of one shared location, shared by the lvalue (SharedVar) and rvalue (SharedRef)
// faces.
template <typename T>
struct SharedLocation {
  std::size_t offset;
  Location loc;

  template <typename U = T>
  requires std::is_array_v<U> SharedRef<std::remove_extent_t<U>> at(const Index& i)
  const {
    constexpr std::size_t extent = std::extent_v<U>;
    if (i.negative || i.value >= extent) shared_out_of_bounds(i.value, extent, i.loc);
    return SharedRef<std::remove_extent_t<U>>(offset + i.value * sizeof(std::remove_extent_t<U>),
                                              i.loc);
  }
};
}  // namespace detail

template <typename T>
class SharedRef {
  static_assert(std::is_trivially_copyable_v<T>, "shared memory holds trivially copyable types");

 public:
  SharedRef(std::size_t offset, Location where) : at_{offset, where} {}
  SharedRef(const SharedRef&) = delete;
  SharedRef& operator=(const SharedRef&) = delete;

  template <typename U = T>
  requires std::is_array_v<U> SharedRef<std::remove_extent_t<U>>
  operator[](const Index& i) && { return at_.at(i); }
  operator detail::element_t<T>() && {  // NOLINT: a read of the element
    return detail::shared_load<T>(at_.offset, at_.loc);
  }
  void operator=(const detail::element_t<T>& value) && {
    detail::shared_store(at_.offset, value, at_.loc);
  }
  void operator=(SharedRef&& other) && {
    detail::shared_store(at_.offset, std::move(other).operator detail::element_t<T>(), at_.loc);
  }
#define SHADOWCTS_EMU_COMPOUND(op)                                                             \
  void operator op##=(const detail::element_t<T>& value) && requires std::is_arithmetic_v<T> { \
    T current = detail::shared_load<T>(at_.offset, at_.loc);                                   \
    current = static_cast<T>(current op value);                                                \
    detail::shared_store(at_.offset, current, at_.loc);                                        \
  }
  SHADOWCTS_EMU_COMPOUND(+)
  SHADOWCTS_EMU_COMPOUND(-)
  SHADOWCTS_EMU_COMPOUND(*)
  SHADOWCTS_EMU_COMPOUND(/)
  SHADOWCTS_EMU_COMPOUND(&)
  SHADOWCTS_EMU_COMPOUND(|)
  SHADOWCTS_EMU_COMPOUND(^)
#undef SHADOWCTS_EMU_COMPOUND
  SharedPtr<T> operator&() && {
    return SharedPtr<T>(at_.offset, at_.loc);
  }

 private:
  detail::SharedLocation<T> at_;
};

// The object a SHADOWCTS_SHARED declaration names. Not copyable: `auto x = name;` does not
// compile, so no access escapes the tracking.
template <typename T>
class SharedVar {
  static_assert(std::is_trivially_copyable_v<T>, "shared memory holds trivially copyable types");

 public:
  SharedVar(std::size_t offset, Location where) : at_{offset, where} {}
  SharedVar(const SharedVar&) = delete;
  SharedVar& operator=(const SharedVar&) = delete;

  template <typename U = T>
  requires std::is_array_v<U> SharedRef<std::remove_extent_t<U>>
  operator[](const Index& i) const { return at_.at(i); }
  // Scalars: reads and writes report the declaration's line (an operator has no call site).
  operator detail::element_t<T>() const {  // NOLINT: a read of the variable
    return detail::shared_load<T>(at_.offset, at_.loc);
  }
  SharedVar& operator=(const detail::element_t<T>& value) {
    detail::shared_store(at_.offset, value, at_.loc);
    return *this;
  }
#define SHADOWCTS_EMU_COMPOUND(op)                                                                \
  SharedVar& operator op##=(const detail::element_t<T>& value) requires std::is_arithmetic_v<T> { \
    T current = detail::shared_load<T>(at_.offset, at_.loc);                                      \
    current = static_cast<T>(current op value);                                                   \
    detail::shared_store(at_.offset, current, at_.loc);                                           \
    return *this;                                                                                 \
  }
  SHADOWCTS_EMU_COMPOUND(+)
  SHADOWCTS_EMU_COMPOUND(-)
  SHADOWCTS_EMU_COMPOUND(*)
  SHADOWCTS_EMU_COMPOUND(/)
  SHADOWCTS_EMU_COMPOUND(&)
  SHADOWCTS_EMU_COMPOUND(|)
  SHADOWCTS_EMU_COMPOUND(^)
#undef SHADOWCTS_EMU_COMPOUND
  SharedPtr<T> operator&() const {
    return SharedPtr<T>(at_.offset, at_.loc);
  }

 private:
  detail::SharedLocation<T> at_;
};

// `extern __shared__ T name[]`: the launch's dynamic shared bytes as an array of T.
template <typename T>
class SharedDynamic {
  static_assert(detail::shared_element_v<T>, "shared memory holds trivially copyable types");

 public:
  SharedDynamic() = default;
  SharedDynamic(const SharedDynamic&) = delete;
  SharedDynamic& operator=(const SharedDynamic&) = delete;
  SharedRef<T> operator[](const Index& i) const {
    const std::size_t extent = detail::dynamic_shared_bytes() / sizeof(T);
    if (i.negative || i.value >= extent) detail::shared_out_of_bounds(i.value, extent, i.loc);
    return SharedRef<T>(i.value * sizeof(T), i.loc);
  }
};

template <typename T>
SharedVar<T> declare_shared(const detail::SharedDecl& decl, Location where = Location::current()) {
  return SharedVar<T>(detail::shared_static(decl, where), where);
}

// ---------------------------------------------------------------------------------------------
// Barriers and warp collectives. The Location defaults name the caller's line in reports.

inline void syncthreads(Location where = Location::current()) {
  detail::block_barrier(detail::Barrier::plain, 0, where);
}
inline int syncthreads_count(int predicate, Location where = Location::current()) {
  return detail::block_barrier(detail::Barrier::count, predicate, where);
}
inline int syncthreads_and(int predicate, Location where = Location::current()) {
  return detail::block_barrier(detail::Barrier::and_, predicate, where);
}
inline int syncthreads_or(int predicate, Location where = Location::current()) {
  return detail::block_barrier(detail::Barrier::or_, predicate, where);
}
inline void syncwarp(unsigned mask = 0xffffffffu, Location where = Location::current()) {
  detail::warp_collective(detail::Collective::syncwarp, mask, 0, 0, warp_size, where);
}
inline unsigned ballot_sync(unsigned mask, int predicate, Location where = Location::current()) {
  return static_cast<unsigned>(detail::warp_collective(detail::Collective::ballot, mask,
                                                       predicate != 0, 0, warp_size, where));
}
inline int any_sync(unsigned mask, int predicate, Location where = Location::current()) {
  return static_cast<int>(
      detail::warp_collective(detail::Collective::any, mask, predicate != 0, 0, warp_size, where));
}
inline int all_sync(unsigned mask, int predicate, Location where = Location::current()) {
  return static_cast<int>(
      detail::warp_collective(detail::Collective::all, mask, predicate != 0, 0, warp_size, where));
}
inline unsigned activemask(Location where = Location::current()) {
  return detail::active_mask(where);
}

namespace detail {
// The types CUDA's __shfl*_sync accept (no half types here).
template <typename T>
inline constexpr bool shuffle_type_v =
    std::is_same_v<T, int> || std::is_same_v<T, unsigned> || std::is_same_v<T, long> ||
    std::is_same_v<T, unsigned long> || std::is_same_v<T, long long> ||
    std::is_same_v<T, unsigned long long> || std::is_same_v<T, float> || std::is_same_v<T, double>;

template <typename T>
T shuffle(Collective kind, unsigned mask, T value, int lane_arg, int width, const Location& where) {
  std::uint64_t bits = 0;
  std::memcpy(&bits, &value, sizeof(T));
  bits = warp_collective(kind, mask, bits, lane_arg, width, where);
  std::memcpy(&value, &bits, sizeof(T));
  return value;
}
}  // namespace detail

template <typename T>
requires detail::shuffle_type_v<T> T shfl_sync(unsigned mask, T value, int src_lane,
                                               int width = warp_size,
                                               Location where = Location::current()) {
  return detail::shuffle(detail::Collective::shfl, mask, value, src_lane, width, where);
}
template <typename T>
requires detail::shuffle_type_v<T> T shfl_up_sync(unsigned mask, T value, unsigned delta,
                                                  int width = warp_size,
                                                  Location where = Location::current()) {
  return detail::shuffle(detail::Collective::shfl_up, mask, value, static_cast<int>(delta), width,
                         where);
}
template <typename T>
requires detail::shuffle_type_v<T> T shfl_down_sync(unsigned mask, T value, unsigned delta,
                                                    int width = warp_size,
                                                    Location where = Location::current()) {
  return detail::shuffle(detail::Collective::shfl_down, mask, value, static_cast<int>(delta), width,
                         where);
}
template <typename T>
requires detail::shuffle_type_v<T> T shfl_xor_sync(unsigned mask, T value, int lane_mask,
                                                   int width = warp_size,
                                                   Location where = Location::current()) {
  return detail::shuffle(detail::Collective::shfl_xor, mask, value, lane_mask, width, where);
}

// ---------------------------------------------------------------------------------------------
// Atomics, with CUDA's overload sets (the value's type follows the address, as with CUDA's
// non-template overloads). Global memory: std::atomic_ref, since blocks run in parallel. Shared
// memory: one OS thread per block, so a plain read-modify-write, tracked as an atomic access.

namespace detail {
template <typename T, typename... U>
inline constexpr bool one_of_v = (std::is_same_v<T, U> || ...);
template <typename T>
inline constexpr bool atomic_add_type_v =
    one_of_v<T, int, unsigned, unsigned long long, float, double>;
template <typename T>
inline constexpr bool atomic_minmax_type_v =
    one_of_v<T, int, unsigned, long long, unsigned long long>;
template <typename T>
inline constexpr bool atomic_bits_type_v = one_of_v<T, int, unsigned, unsigned long long>;
template <typename T>
inline constexpr bool atomic_exch_type_v = one_of_v<T, int, unsigned, unsigned long long, float>;
template <typename T>
inline constexpr bool atomic_cas_type_v = one_of_v<T, int, unsigned, unsigned long long>;

// Applies op (old -> new) atomically at a global address and returns the old value.
template <typename T, typename Op>
T global_rmw(T* address, Op op) {
  yield_point();
  std::atomic_ref<T> ref(*address);
  T old = ref.load(std::memory_order_relaxed);
  while (!ref.compare_exchange_weak(old, op(old), std::memory_order_relaxed)) {
  }
  return old;
}
template <typename T, typename Op>
T shared_rmw(const SharedPtr<T>& address, Op op) {
  std::byte* base = untracked_shared_base;
  if (base == nullptr) {
    shared_access(address.offset(), sizeof(T), Access::atomic, address.where());
    base = shared_base();
  }
  T old;
  std::memcpy(&old, base + address.offset(), sizeof(T));
  const T updated = op(old);
  std::memcpy(base + address.offset(), &updated, sizeof(T));
  return old;
}
template <typename T, typename Op>
T rmw(T* address, Op op) {
  return global_rmw(address, op);
}
template <typename T, typename Op>
T rmw(const SharedPtr<T>& address, Op op) {
  return shared_rmw(address, op);
}
template <typename P>
struct pointee;
template <typename T>
struct pointee<T*> {
  using type = T;
};
template <typename T>
struct pointee<SharedPtr<T>> {
  using type = T;
};
template <typename P>
using pointee_t = typename pointee<P>::type;
}  // namespace detail

template <typename P, typename T = detail::pointee_t<P>>
requires detail::atomic_add_type_v<T> T atomic_add(P address, std::type_identity_t<T> value) {
  return detail::rmw(address, [value](T old) { return static_cast<T>(old + value); });
}
template <typename P, typename T = detail::pointee_t<P>>
requires detail::atomic_minmax_type_v<T> T atomic_min(P address, std::type_identity_t<T> value) {
  return detail::rmw(address, [value](T old) { return value < old ? value : old; });
}
template <typename P, typename T = detail::pointee_t<P>>
requires detail::atomic_minmax_type_v<T> T atomic_max(P address, std::type_identity_t<T> value) {
  return detail::rmw(address, [value](T old) { return value > old ? value : old; });
}
template <typename P, typename T = detail::pointee_t<P>>
requires detail::atomic_bits_type_v<T> T atomic_and(P address, std::type_identity_t<T> value) {
  return detail::rmw(address, [value](T old) { return static_cast<T>(old & value); });
}
template <typename P, typename T = detail::pointee_t<P>>
requires detail::atomic_bits_type_v<T> T atomic_or(P address, std::type_identity_t<T> value) {
  return detail::rmw(address, [value](T old) { return static_cast<T>(old | value); });
}
template <typename P, typename T = detail::pointee_t<P>>
requires detail::atomic_bits_type_v<T> T atomic_xor(P address, std::type_identity_t<T> value) {
  return detail::rmw(address, [value](T old) { return static_cast<T>(old ^ value); });
}
template <typename P, typename T = detail::pointee_t<P>>
requires detail::atomic_exch_type_v<T> T atomic_exch(P address, std::type_identity_t<T> value) {
  return detail::rmw(address, [value](T) { return value; });
}
template <typename P, typename T = detail::pointee_t<P>>
requires detail::atomic_cas_type_v<T> T atomic_cas(P address, std::type_identity_t<T> compare,
                                                   std::type_identity_t<T> value) {
  return detail::rmw(address, [compare, value](T old) { return old == compare ? value : old; });
}

// ---------------------------------------------------------------------------------------------
// Launch: SHADOWCTS_LAUNCH(kernel, grid, block, shared)(args...) converts the arguments to the
// kernel's parameter types once, as a launch does, and runs the grid before returning.

template <typename... Params>
class Launch {
  static_assert((std::is_trivially_copyable_v<Params> && ...),
                "kernel parameters are copied to the device: trivially copyable types only");

 public:
  Launch(void (*kernel)(Params...), const char* name, Dim3 grid, Dim3 block,
         std::size_t dynamic_shared, Location where = Location::current())
      : kernel_(kernel),
        name_(name),
        grid_(grid),
        block_(block),
        shared_(dynamic_shared),
        where_(where) {}

  template <typename... Args>
  requires(sizeof...(Args) == sizeof...(Params)) void operator()(Args&&... args) const {
    const Bound bound{kernel_, std::tuple<Params...>(std::forward<Args>(args)...)};
    detail::launch(
        name_, grid_, block_, shared_, where_,
        [](const void* p) {
          const Bound& b = *static_cast<const Bound*>(p);
          std::apply(b.kernel, b.args);
        },
        &bound);
  }

 private:
  struct Bound {
    void (*kernel)(Params...);
    std::tuple<Params...> args;
  };
  void (*kernel_)(Params...);
  const char* name_;
  Dim3 grid_, block_;
  std::size_t shared_;
  Location where_;
};

// ---------------------------------------------------------------------------------------------
// The runtime API subset, on host memory ("device" memory is ordinary heap memory here).

enum EmuError { cudaSuccess = 0, cudaErrorMemoryAllocation = 2, cudaErrorInvalidValue = 1 };
enum EmuMemcpyKind {
  cudaMemcpyHostToHost = 0,
  cudaMemcpyHostToDevice = 1,
  cudaMemcpyDeviceToHost = 2,
  cudaMemcpyDeviceToDevice = 3,
  cudaMemcpyDefault = 4
};
EmuError device_malloc(void** pointer, std::size_t bytes);
template <typename T>
EmuError device_malloc(T** pointer, std::size_t bytes) {
  void* p = nullptr;
  const EmuError status = device_malloc(&p, bytes);
  *pointer = static_cast<T*>(p);
  return status;
}
EmuError device_free(void* pointer);
EmuError device_memcpy(void* destination, const void* source, std::size_t bytes,
                       EmuMemcpyKind kind);
EmuError device_memset(void* destination, int value, std::size_t bytes);
// Launches run to completion and throw on failure, so these have nothing left to report.
inline EmuError device_synchronize() {
  return cudaSuccess;
}
inline EmuError get_last_error() {
  return cudaSuccess;
}
const char* error_name(EmuError status);
const char* error_string(EmuError status);

}  // namespace shadowcts::emu
