#include "gpu/emulator/emulator.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdlib>
#include <deque>
#include <exception>
#include <limits>
#include <memory>
#include <mutex>
#include <random>
#include <sstream>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#if defined(__SANITIZE_ADDRESS__)
#define SHADOWCTS_EMU_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SHADOWCTS_EMU_ASAN 1
#endif
#endif
#ifndef SHADOWCTS_EMU_ASAN
#define SHADOWCTS_EMU_ASAN 0
#endif
#if SHADOWCTS_EMU_ASAN
#include <sanitizer/common_interface_defs.h>
#endif

#include <boost/context/fiber.hpp>
#include <boost/context/protected_fixedsize_stack.hpp>

#include "shadowcts/phase_progress.h"

namespace shadowcts::emu {

namespace ctx = boost::context;

// ---------------------------------------------------------------------------------------------
// Options

namespace {

Options options_from_environment() {
  Options options;
  if (const char* schedule = std::getenv("SHADOWCTS_EMU_SCHEDULE")) {
    const std::string s(schedule);
    if (s.rfind("random", 0) == 0) {
      options.schedule = Schedule::random;
      if (const auto colon = s.find(':'); colon != std::string::npos) {
        options.seed = std::strtoull(s.c_str() + colon + 1, nullptr, 10);
      }
    }
  }
  if (const char* races = std::getenv("SHADOWCTS_EMU_CHECK_RACES")) {
    options.check_races = std::string(races) == "1";
  }
  return options;
}

Options& thread_options() {
  static const Options defaults = options_from_environment();
  thread_local Options options = defaults;
  return options;
}

}  // namespace

Options current_options() {
  return thread_options();
}

ScopedOptions::ScopedOptions(const Options& options) : saved_(thread_options()) {
  thread_options() = options;
}

ScopedOptions::~ScopedOptions() {
  thread_options() = saved_;
}

// ---------------------------------------------------------------------------------------------
// Errors

const char* to_string(ErrorKind kind) {
  switch (kind) {
    case ErrorKind::invalid_launch:
      return "invalid launch";
    case ErrorKind::invalid_argument:
      return "invalid argument";
    case ErrorKind::barrier_divergence:
      return "divergent barrier";
    case ErrorKind::warp_lane_missing:
      return "warp lane does not arrive";
    case ErrorKind::warp_lane_exited:
      return "warp lane has exited";
    case ErrorKind::shuffle_inactive_lane:
      return "shuffle from an inactive lane";
    case ErrorKind::shared_race:
      return "shared-memory race";
    case ErrorKind::shared_uninitialized:
      return "uninitialized shared-memory read";
    case ErrorKind::shared_out_of_bounds:
      return "shared-memory index out of bounds";
    case ErrorKind::deadlock:
      return "deadlock";
    case ErrorKind::outside_kernel:
      return "device call outside a kernel";
  }
  return "?";
}

namespace {

std::string format_dim(Uint3 d) {
  // A stream, not string concatenation: GCC 12 reports a false -Wrestrict on the latter.
  std::ostringstream out;
  out << "(" << d.x << "," << d.y << "," << d.z << ")";
  return out.str();
}

std::string format_error(ErrorKind kind, const std::string& kernel, Uint3 block, Uint3 thread,
                         const std::string& file, unsigned line, const std::string& message) {
  std::ostringstream out;
  out << "cuda-emu: " << to_string(kind) << " in kernel " << kernel << ", block "
      << format_dim(block) << ", thread " << format_dim(thread) << ", at " << file << ":" << line
      << ": " << message;
  return out.str();
}

}  // namespace

EmulatorError::EmulatorError(ErrorKind kind_, std::string kernel_, Uint3 block_, Uint3 thread_,
                             std::string file_, unsigned line_, const std::string& message)
    : std::runtime_error(format_error(kind_, kernel_, block_, thread_, file_, line_, message)),
      kind(kind_),
      kernel(std::move(kernel_)),
      block(block_),
      thread(thread_),
      file(std::move(file_)),
      line(line_) {}

namespace detail {

thread_local std::byte* untracked_shared_base = nullptr;

namespace {

// ---------------------------------------------------------------------------------------------
// Fiber stacks, reused across the blocks an OS thread runs (creating a block's fibers is then
// cheap). Guard pages turn a kernel's stack overflow into a crash instead of silent corruption.

constexpr std::size_t stack_bytes = 256 * 1024;

class StackPool {
 public:
  ~StackPool() {
    ctx::protected_fixedsize_stack allocator(stack_bytes);
    for (ctx::stack_context& stack : free_) allocator.deallocate(stack);
  }
  ctx::stack_context take() {
    if (free_.empty()) return ctx::protected_fixedsize_stack(stack_bytes).allocate();
    const ctx::stack_context stack = free_.back();
    free_.pop_back();
    return stack;
  }
  void give(const ctx::stack_context& stack) { free_.push_back(stack); }

 private:
  std::vector<ctx::stack_context> free_;
};

StackPool& stack_pool() {
  thread_local StackPool pool;
  return pool;
}

// AddressSanitizer must be told of every switch between stacks; otherwise it takes a fiber's
// frames for the scheduler's and reports false errors when an exception unwinds them.
struct StackBounds {
  const void* bottom = nullptr;
  std::size_t size = 0;
};

void start_switch(void** fake_stack, const StackBounds& to) {
#if SHADOWCTS_EMU_ASAN
  __sanitizer_start_switch_fiber(fake_stack, to.bottom, to.size);
#else
  (void)fake_stack;
  (void)to;
#endif
}

void finish_switch(void* fake_stack, StackBounds* from) {
#if SHADOWCTS_EMU_ASAN
  const void* bottom = nullptr;
  std::size_t size = 0;
  __sanitizer_finish_switch_fiber(fake_stack, &bottom, &size);
  if (from != nullptr) *from = {bottom, size};
#else
  (void)fake_stack;
  (void)from;
#endif
}

// Hands out pooled stacks and remembers where each fiber's stack lies (for the sanitizer).
struct PooledStack {
  StackBounds* bounds;
  ctx::stack_context allocate() {
    const ctx::stack_context stack = stack_pool().take();
    *bounds = {static_cast<const char*>(stack.sp) - stack.size, stack.size};
    return stack;
  }
  void deallocate(ctx::stack_context& stack) { stack_pool().give(stack); }
};

// Thrown in a suspended thread when its block is torn down after an error: the thread's frames
// unwind on its own stack, and the fiber then ends normally (no forced unwind by Boost).
struct Unwinding {};

// ---------------------------------------------------------------------------------------------
// One block: its threads (fibers), barrier, warps, shared arena and race tracking.

enum class Wait : std::uint8_t { runnable, barrier, warp, activemask, exited };

struct Thread {
  ThreadInfo info;
  unsigned linear = 0, warp = 0, lane = 0;
  ctx::fiber fiber, scheduler;
  Wait wait = Wait::runnable;
  Location where;  // of the barrier or collective it waits at
  const char* what = "";
  // Collective arguments and result.
  Collective collective = Collective::syncwarp;
  unsigned mask = 0;
  std::uint64_t value = 0, result = 0;
  int lane_arg = 0, width = warp_size;
  // Per lane of its warp: the warp's sync sequence after the last __syncwarp this thread took
  // part in together with that lane.
  std::array<unsigned, warp_size> synced_with{};
  StackBounds stack;
};

struct WarpGroup {
  Collective kind;
  unsigned mask, arrived;
};

struct Warp {
  unsigned lanes = 0;   // lanes that exist (a partial last warp has fewer)
  unsigned exited = 0;  // lanes that have returned
  unsigned sequence = 1;
  std::vector<WarpGroup> pending;
};

// Per shared byte: the last write and the reads since the barrier epoch they carry.
struct ByteState {
  std::uint32_t write_epoch = 0, read_epoch = 0;
  std::uint32_t write_sequence = 0, read_sequence = 0;
  std::uint16_t writer = 0, reader = 0;
  std::uint16_t reader_warp = 0;
};
constexpr std::uint16_t many = 0xffff;
constexpr std::uint16_t atomic_bit = 0x8000;  // on writer: the write was atomic
constexpr std::uint16_t thread_bits = 0x7fff;

// Storage an OS thread reuses for every block it runs.
struct WorkerStorage {
  std::vector<std::byte> arena;
  std::vector<ByteState> bytes;
  std::uint32_t epoch = 0;
};

WorkerStorage& worker_storage() {
  thread_local WorkerStorage storage;
  return storage;
}

const char* barrier_name(Barrier kind) {
  switch (kind) {
    case Barrier::plain:
      return "__syncthreads";
    case Barrier::count:
      return "__syncthreads_count";
    case Barrier::and_:
      return "__syncthreads_and";
    case Barrier::or_:
      return "__syncthreads_or";
  }
  return "?";
}

const char* collective_name(Collective kind) {
  switch (kind) {
    case Collective::syncwarp:
      return "__syncwarp";
    case Collective::shfl:
      return "__shfl_sync";
    case Collective::shfl_up:
      return "__shfl_up_sync";
    case Collective::shfl_down:
      return "__shfl_down_sync";
    case Collective::shfl_xor:
      return "__shfl_xor_sync";
    case Collective::ballot:
      return "__ballot_sync";
    case Collective::any:
      return "__any_sync";
    case Collective::all:
      return "__all_sync";
  }
  return "?";
}

std::string where_text(const Location& where) {
  return std::string(where.file_name()) + ":" + std::to_string(where.line());
}

bool same_site(const Location& a, const Location& b) {
  return a.line() == b.line() && a.column() == b.column() &&
         std::strcmp(a.file_name(), b.file_name()) == 0;
}

std::string hex(unsigned mask) {
  std::ostringstream out;
  out << "0x" << std::hex << mask;
  return out.str();
}

struct LaunchState {
  const char* kernel;
  Dim3 grid, block;
  std::size_t dynamic_shared;
  ThreadEntry entry;
  const void* bound;
  Options options;
};

class Block {
 public:
  Block(const LaunchState& launch, std::size_t linear_block);
  ~Block();
  Block(const Block&) = delete;
  Block& operator=(const Block&) = delete;

  void run();

  Thread& current() { return *current_; }
  [[noreturn]] void fail(ErrorKind kind, const Thread& thread, const Location& where,
                         const std::string& message) const;

  int barrier(Barrier kind, int predicate, const Location& where);
  std::uint64_t collective(Collective kind, unsigned mask, std::uint64_t value, int lane_arg,
                           int width, const Location& where);
  unsigned activemask(const Location& where);
  void yield_point();

  std::size_t shared_static(const SharedDecl& decl, const Location& where);
  std::size_t dynamic_shared_bytes() const { return launch_.dynamic_shared; }
  std::byte* shared_base() { return storage_.arena.data(); }
  void shared_access(std::size_t offset, std::size_t size, Access access, const Location& where);

 private:
  void suspend();  // back to the scheduler; returns when this thread is resumed
  void make_runnable(Thread& thread);
  Thread* pick();
  void thread_exited(Thread& thread);
  bool resolve_activemasks();
  [[noreturn]] void report_deadlock();
  void complete(Warp& warp, std::size_t group_index);
  std::uint16_t thread_id(const Thread& t) const { return static_cast<std::uint16_t>(t.linear); }
  bool warp_ordered(const Thread& accessor, std::uint16_t other, std::uint32_t sequence) const;
  bool warp_ordered_with_all(const Thread& accessor, std::uint32_t sequence) const;

  const LaunchState& launch_;
  Uint3 index_;
  std::vector<Thread> threads_;
  std::vector<Warp> warps_;
  Thread* current_ = nullptr;
  unsigned exited_ = 0;
  // The barrier being gathered.
  unsigned barrier_arrived_ = 0;
  Barrier barrier_kind_ = Barrier::plain;
  Location barrier_where_;
  unsigned barrier_first_ = 0;
  int barrier_accumulator_ = 0;
  // Scheduling.
  std::deque<Thread*> queue_;   // run_until_block: FIFO
  std::vector<Thread*> ready_;  // random: any order
  std::mt19937_64 random_;
  std::bernoulli_distribution yield_coin_{0.5};
  std::exception_ptr error_;
  // Shared memory.
  WorkerStorage& storage_;
  std::size_t shared_top_;
  std::vector<std::pair<const SharedDecl*, std::size_t>> statics_;
  bool track_;
  std::uint32_t first_epoch_ = 0;
  StackBounds scheduler_stack_;
  bool unwinding_ = false;
};

thread_local Block* t_block = nullptr;

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

constexpr std::size_t align_up(std::size_t value, std::size_t alignment) {
  return (value + alignment - 1) / alignment * alignment;
}

Block::Block(const LaunchState& launch, std::size_t linear_block)
    : launch_(launch),
      random_(splitmix64(launch.options.seed ^ splitmix64(linear_block))),
      storage_(worker_storage()),
      shared_top_(align_up(launch.dynamic_shared, 16)),
      track_(launch.options.check_races) {
  const Dim3 g = launch.grid, b = launch.block;
  index_ = {static_cast<unsigned>(linear_block % g.x),
            static_cast<unsigned>(linear_block / g.x % g.y),
            static_cast<unsigned>(linear_block / (std::size_t(g.x) * g.y))};
  const unsigned count = b.x * b.y * b.z;
  threads_.resize(count);
  warps_.resize((count + warp_size - 1) / warp_size);
  for (unsigned i = 0; i < count; ++i) {
    Thread& t = threads_[i];
    t.info.thread_idx = {i % b.x, i / b.x % b.y, i / (b.x * b.y)};
    t.info.block_idx = index_;
    t.info.block_dim = b;
    t.info.grid_dim = g;
    t.linear = i;
    t.warp = i / warp_size;
    t.lane = i % warp_size;
    warps_[t.warp].lanes |= 1u << t.lane;
  }
  // The arena never reallocates while the block runs: accessors hold offsets into it.
  if (storage_.arena.size() < max_shared_bytes) storage_.arena.resize(max_shared_bytes);
  std::fill_n(storage_.arena.begin(), launch.dynamic_shared, std::byte{0xff});
  if (track_) {
    if (storage_.bytes.size() < max_shared_bytes) storage_.bytes.resize(max_shared_bytes);
    if (storage_.epoch > std::numeric_limits<std::uint32_t>::max() - (1u << 30)) {
      std::fill(storage_.bytes.begin(), storage_.bytes.end(), ByteState{});
      storage_.epoch = 0;
    }
    first_epoch_ = ++storage_.epoch;
  }
}

Block::~Block() {
  // Threads still suspended (after an error) are resumed once more: each throws Unwinding where
  // it waits, or ends at once if it never started.
  Block* const saved = t_block;
  t_block = this;
  unwinding_ = true;
  for (Thread& t : threads_) {
    if (!t.fiber) continue;
    current_ = &t;
    void* fake_stack = nullptr;
    start_switch(&fake_stack, t.stack);
    t.fiber = std::move(t.fiber).resume();
    finish_switch(fake_stack, nullptr);
  }
  t_block = saved;
}

void Block::fail(ErrorKind kind, const Thread& thread, const Location& where,
                 const std::string& message) const {
  throw EmulatorError(kind, launch_.kernel, index_, thread.info.thread_idx, where.file_name(),
                      where.line(), message);
}

void Block::suspend() {
  Thread& self = *current_;
#if !SHADOWCTS_EMU_ASAN
  // Straight to the thread the scheduler would pick next: one switch instead of two. The
  // scheduler's continuation travels with control, so whichever thread has none left to run
  // returns to the scheduler. (Under AddressSanitizer every switch goes through the scheduler,
  // whose stack bounds the annotations need.)
  if (Thread* next = pick()) {
    current_ = next;
    if (next != &self) {
      self.scheduler =
          std::move(next->fiber).resume_with([&self](ctx::fiber&& suspended) -> ctx::fiber {
            self.fiber = std::move(suspended);
            return std::move(self.scheduler);
          });
    }
    if (unwinding_) throw Unwinding{};
    return;
  }
#endif
  void* fake_stack = nullptr;
  start_switch(&fake_stack, scheduler_stack_);
  self.scheduler = std::move(self.scheduler).resume();
  finish_switch(fake_stack, &scheduler_stack_);
  if (unwinding_) throw Unwinding{};
}

void Block::make_runnable(Thread& thread) {
  thread.wait = Wait::runnable;
  if (launch_.options.schedule == Schedule::random) {
    ready_.push_back(&thread);
  } else {
    queue_.push_back(&thread);
  }
}

Thread* Block::pick() {
  if (launch_.options.schedule == Schedule::random) {
    if (ready_.empty()) return nullptr;
    std::uniform_int_distribution<std::size_t> index(0, ready_.size() - 1);
    const std::size_t i = index(random_);
    Thread* t = ready_[i];
    ready_[i] = ready_.back();
    ready_.pop_back();
    return t;
  }
  if (queue_.empty()) return nullptr;
  Thread* t = queue_.front();
  queue_.pop_front();
  return t;
}

void Block::run() {
  struct Current {
    explicit Current(Block* block) {
      t_block = block;
      untracked_shared_base = block->track_ || block->launch_.options.schedule == Schedule::random
                                  ? nullptr
                                  : block->shared_base();
    }
    ~Current() {
      t_block = nullptr;
      untracked_shared_base = nullptr;
    }
  } current(this);
  for (Thread& t : threads_) {
    t.fiber =
        ctx::fiber(std::allocator_arg, PooledStack{&t.stack}, [this, &t](ctx::fiber&& scheduler) {
          finish_switch(nullptr, &scheduler_stack_);
          t.scheduler = std::move(scheduler);
          if (!unwinding_) {
            try {
              launch_.entry(launch_.bound);
              thread_exited(t);
            } catch (const Unwinding&) {
              // torn down after another thread's error
            } catch (const ctx::detail::forced_unwind&) {
              throw;  // Boost unwinds a fiber it destroys: let it
            } catch (...) {
              error_ = std::current_exception();
            }
          }
          start_switch(nullptr, scheduler_stack_);  // this stack is done
          return std::move(t.scheduler);
        });
    make_runnable(t);
  }
  while (exited_ < threads_.size()) {
    Thread* next = pick();
    if (next == nullptr) {
      if (resolve_activemasks()) continue;
      report_deadlock();
    }
    current_ = next;
    t_block = this;
    void* fake_stack = nullptr;
    start_switch(&fake_stack, next->stack);
    // Threads may have handed control on: the one that comes back is the current one.
    ctx::fiber back = std::move(next->fiber).resume();
    current_->fiber = std::move(back);
    finish_switch(fake_stack, nullptr);
    if (error_) std::rethrow_exception(error_);
  }
}

void Block::yield_point() {
  if (launch_.options.schedule != Schedule::random || !yield_coin_(random_)) return;
  make_runnable(*current_);
  suspend();
}

// --- block barriers -----------------------------------------------------------------------

int Block::barrier(Barrier kind, int predicate, const Location& where) {
  yield_point();
  Thread& self = *current_;
  if (exited_ != 0) {
    const auto exited = std::find_if(threads_.begin(), threads_.end(),
                                     [](const Thread& t) { return t.wait == Wait::exited; });
    fail(ErrorKind::barrier_divergence, *exited, where,
         "this thread exited without reaching " + std::string(barrier_name(kind)) +
             ", which thread " + format_dim(self.info.thread_idx) + " waits at");
  }
  if (barrier_arrived_ == 0) {
    barrier_kind_ = kind;
    barrier_where_ = where;
    barrier_first_ = self.linear;
    barrier_accumulator_ = kind == Barrier::and_ ? 1 : 0;
  } else if (kind != barrier_kind_ || !same_site(where, barrier_where_)) {
    fail(ErrorKind::barrier_divergence, self, where,
         "this thread waits at " + std::string(barrier_name(kind)) + " here while thread " +
             format_dim(threads_[barrier_first_].info.thread_idx) + " waits at " +
             barrier_name(barrier_kind_) + " at " + where_text(barrier_where_));
  }
  switch (kind) {
    case Barrier::plain:
      break;
    case Barrier::count:
      barrier_accumulator_ += predicate != 0;
      break;
    case Barrier::and_:
      barrier_accumulator_ &= predicate != 0;
      break;
    case Barrier::or_:
      barrier_accumulator_ |= predicate != 0;
      break;
  }
  ++barrier_arrived_;
  self.wait = Wait::barrier;
  self.where = where;
  self.what = barrier_name(kind);
  if (barrier_arrived_ == threads_.size()) {
    // Everyone is here: a new epoch for race tracking, and all threads continue in order.
    if (track_) ++storage_.epoch;
    barrier_arrived_ = 0;
    for (Thread& t : threads_) {
      t.result = static_cast<std::uint64_t>(barrier_accumulator_);
      make_runnable(t);
    }
  }
  suspend();
  return static_cast<int>(self.result);
}

// --- warp collectives -----------------------------------------------------------------------

std::uint64_t Block::collective(Collective kind, unsigned mask, std::uint64_t value, int lane_arg,
                                int width, const Location& where) {
  yield_point();
  Thread& self = *current_;
  Warp& warp = warps_[self.warp];
  if ((mask & (1u << self.lane)) == 0) {
    fail(ErrorKind::invalid_argument, self, where,
         std::string(collective_name(kind)) + " with mask " + hex(mask) +
             " that does not name the calling lane " + std::to_string(self.lane));
  }
  if (width < 1 || width > warp_size || !std::has_single_bit(static_cast<unsigned>(width))) {
    fail(ErrorKind::invalid_argument, self, where,
         std::string(collective_name(kind)) + " with width " + std::to_string(width) +
             " (a power of two up to 32)");
  }
  if (const unsigned absent = mask & ~warp.lanes) {
    fail(ErrorKind::warp_lane_exited, self, where,
         std::string(collective_name(kind)) + " with mask " + hex(mask) + " names lane " +
             std::to_string(std::countr_zero(absent)) + ", which does not exist (the block's " +
             "last warp has " + std::to_string(std::popcount(warp.lanes)) + " lanes)");
  }
  if (const unsigned gone = mask & warp.exited) {
    fail(ErrorKind::warp_lane_exited, self, where,
         std::string(collective_name(kind)) + " with mask " + hex(mask) + " names lane " +
             std::to_string(std::countr_zero(gone)) + ", which has exited");
  }
  self.collective = kind;
  self.mask = mask;
  self.value = value;
  self.lane_arg = lane_arg;
  self.width = width;
  self.wait = Wait::warp;
  self.where = where;
  self.what = collective_name(kind);

  // Join the pending collective of the same kind and mask, or open one.
  std::size_t group_index = warp.pending.size();
  for (std::size_t i = 0; i < warp.pending.size(); ++i) {
    const WarpGroup& g = warp.pending[i];
    if (g.kind == kind && g.mask == mask && (g.arrived & (1u << self.lane)) == 0) {
      group_index = i;
      break;
    }
  }
  if (group_index == warp.pending.size()) warp.pending.push_back({kind, mask, 0});
  warp.pending[group_index].arrived |= 1u << self.lane;
  if (warp.pending[group_index].arrived == mask) complete(warp, group_index);
  suspend();
  return self.result;
}

void Block::complete(Warp& warp, std::size_t group_index) {
  const WarpGroup group = warp.pending[group_index];
  warp.pending.erase(warp.pending.begin() + static_cast<std::ptrdiff_t>(group_index));
  const unsigned base = static_cast<unsigned>(&warp - warps_.data()) * warp_size;
  auto lane_thread = [&](unsigned lane) -> Thread& { return threads_[base + lane]; };

  unsigned votes = 0;
  for (unsigned m = group.mask; m != 0; m &= m - 1) {
    const unsigned lane = static_cast<unsigned>(std::countr_zero(m));
    if (lane_thread(lane).value != 0) votes |= 1u << lane;
  }
  if (group.kind == Collective::syncwarp) ++warp.sequence;
  for (unsigned m = group.mask; m != 0; m &= m - 1) {
    const unsigned lane = static_cast<unsigned>(std::countr_zero(m));
    Thread& t = lane_thread(lane);
    const unsigned width = static_cast<unsigned>(t.width);
    const unsigned segment = lane & ~(width - 1);
    const unsigned arg = static_cast<unsigned>(t.lane_arg);
    // CUDA's source lane rules: idx wraps within the segment; up/down/xor past the segment
    // keep the caller's own value.
    unsigned source = lane;
    bool in_range = true;
    switch (group.kind) {
      case Collective::shfl:
        source = segment + (arg & (width - 1));
        break;
      case Collective::shfl_up:
        in_range = arg <= lane - segment;
        source = lane - arg;
        break;
      case Collective::shfl_down:
        in_range = arg < segment + width - lane;
        source = lane + arg;
        break;
      case Collective::shfl_xor:
        source = lane ^ (arg & (warp_size - 1));
        in_range = source < segment + width;
        break;
      default:
        break;
    }
    switch (group.kind) {
      case Collective::syncwarp:
        t.result = 0;
        for (unsigned peers = group.mask; peers != 0; peers &= peers - 1) {
          t.synced_with[static_cast<unsigned>(std::countr_zero(peers))] = warp.sequence;
        }
        break;
      case Collective::ballot:
        t.result = votes;
        break;
      case Collective::any:
        t.result = votes != 0;
        break;
      case Collective::all:
        t.result = votes == group.mask;
        break;
      default:
        if (!in_range) {
          t.result = t.value;
        } else if ((group.mask & (1u << source)) == 0) {
          fail(ErrorKind::shuffle_inactive_lane, t, t.where,
               std::string(collective_name(group.kind)) + " of lane " + std::to_string(lane) +
                   " reads lane " + std::to_string(source) + ", which is not in the mask " +
                   hex(group.mask));
        } else {
          t.result = lane_thread(source).value;
        }
    }
  }
  for (unsigned m = group.mask; m != 0; m &= m - 1) {
    make_runnable(lane_thread(static_cast<unsigned>(std::countr_zero(m))));
  }
}

unsigned Block::activemask(const Location& where) {
  yield_point();
  Thread& self = *current_;
  self.wait = Wait::activemask;
  self.where = where;
  self.what = "__activemask";
  suspend();
  return static_cast<unsigned>(self.result);
}

// The lanes of a warp that stand at the same __activemask once nothing else can run are the
// converged ones: the answer does not depend on the schedule.
bool Block::resolve_activemasks() {
  bool any = false;
  for (Thread& t : threads_) {
    if (t.wait != Wait::activemask) continue;
    unsigned mask = 0;
    for (unsigned lane = 0; lane < warp_size; ++lane) {
      const unsigned i = t.warp * warp_size + lane;
      if (i < threads_.size() && threads_[i].wait == Wait::activemask &&
          same_site(threads_[i].where, t.where)) {
        mask |= 1u << lane;
      }
    }
    t.result = mask;
    any = true;
  }
  for (Thread& t : threads_) {
    if (t.wait == Wait::activemask) make_runnable(t);
  }
  return any;
}

void Block::thread_exited(Thread& thread) {
  thread.wait = Wait::exited;
  ++exited_;
  Warp& warp = warps_[thread.warp];
  warp.exited |= 1u << thread.lane;
  if (barrier_arrived_ != 0) {
    const Thread& waiter = threads_[barrier_first_];
    fail(ErrorKind::barrier_divergence, thread, barrier_where_,
         "this thread exited while " + std::to_string(barrier_arrived_) + " thread(s), first " +
             format_dim(waiter.info.thread_idx) + ", wait at " + barrier_name(barrier_kind_) +
             " here");
  }
  for (const WarpGroup& group : warp.pending) {
    if (group.mask & (1u << thread.lane)) {
      const Thread& waiter = threads_[thread.warp * warp_size +
                                      static_cast<unsigned>(std::countr_zero(group.arrived))];
      fail(ErrorKind::warp_lane_exited, waiter, waiter.where,
           std::string(collective_name(group.kind)) + " with mask " + hex(group.mask) +
               " names lane " + std::to_string(thread.lane) + ", which has exited");
    }
  }
}

void Block::report_deadlock() {
  for (const Warp& warp : warps_) {
    for (const WarpGroup& group : warp.pending) {
      const unsigned base = static_cast<unsigned>(&warp - warps_.data()) * warp_size;
      const Thread& waiter =
          threads_[base + static_cast<unsigned>(std::countr_zero(group.arrived))];
      const unsigned missing_lane =
          static_cast<unsigned>(std::countr_zero(group.mask & ~group.arrived));
      const Thread& missing = threads_[base + missing_lane];
      const std::string head = std::string(collective_name(group.kind)) + " with mask " +
                               hex(group.mask) + " names lane " + std::to_string(missing_lane);
      if (missing.wait == Wait::barrier) {
        fail(ErrorKind::warp_lane_missing, waiter, waiter.where,
             head + ", which does not arrive: it waits at " + missing.what + " at " +
                 where_text(missing.where));
      }
      fail(ErrorKind::deadlock, waiter, waiter.where,
           head + ", which waits at " + missing.what + " at " + where_text(missing.where) +
               " instead: no thread of the block can run");
    }
  }
  const auto waiting = std::find_if(threads_.begin(), threads_.end(),
                                    [](const Thread& t) { return t.wait != Wait::exited; });
  fail(ErrorKind::deadlock, *waiting, waiting->where,
       std::string("no thread of the block can run; this one waits at ") + waiting->what);
}

// --- shared memory ------------------------------------------------------------------------

std::size_t Block::shared_static(const SharedDecl& decl, const Location& where) {
  for (const auto& [known, offset] : statics_) {
    if (known == &decl) return offset;
  }
  const std::size_t offset = align_up(shared_top_, std::max<std::size_t>(decl.align, 1));
  if (offset + decl.size > max_shared_bytes) {
    fail(ErrorKind::invalid_launch, *current_, where,
         "shared memory '" + std::string(decl.name) + "' (" + std::to_string(decl.size) +
             " bytes) takes the block past " + std::to_string(max_shared_bytes) +
             " bytes of static and dynamic shared memory");
  }
  shared_top_ = offset + decl.size;
  // A fill that makes an uninitialized read visible in results even without tracking.
  std::fill_n(storage_.arena.begin() + static_cast<std::ptrdiff_t>(offset), decl.size,
              std::byte{0xff});
  statics_.emplace_back(&decl, offset);
  return offset;
}

bool Block::warp_ordered(const Thread& accessor, std::uint16_t other,
                         std::uint32_t sequence) const {
  // Lanes of one warp are ordered by a __syncwarp both took part in after the access.
  if (other == many || (other & atomic_bit) != 0) return false;
  const Thread& o = threads_[other];
  return o.warp == accessor.warp && accessor.synced_with[o.lane] > sequence;
}

bool Block::warp_ordered_with_all(const Thread& accessor, std::uint32_t sequence) const {
  // Several readers of one warp: the accessor must have synced with every lane still running
  // after the reads (a lane that has exited reads nothing more).
  const Warp& warp = warps_[accessor.warp];
  for (unsigned m = warp.lanes & ~warp.exited; m != 0; m &= m - 1) {
    const unsigned lane = static_cast<unsigned>(std::countr_zero(m));
    if (lane != accessor.lane && accessor.synced_with[lane] <= sequence) return false;
  }
  return true;
}

void Block::shared_access(std::size_t offset, std::size_t size, Access access,
                          const Location& where) {
  yield_point();
  if (!track_) return;
  Thread& self = *current_;
  const std::uint32_t epoch = storage_.epoch;
  const std::uint16_t me = thread_id(self);
  const std::uint32_t sequence = warps_[self.warp].sequence;
  const std::uint16_t my_warp = static_cast<std::uint16_t>(self.warp);
  auto race = [&](const char* mine, const char* theirs, std::uint16_t other, std::size_t byte) {
    const std::string who =
        (other & thread_bits) == (many & thread_bits)
            ? std::string("several threads")
            : "thread " + format_dim(threads_[other & thread_bits].info.thread_idx);
    fail(ErrorKind::shared_race, self, where,
         std::string(mine) + " of shared byte " + std::to_string(byte) + " races with " + who +
             "'s " + theirs + " since the last barrier");
  };
  for (std::size_t i = offset; i < offset + size; ++i) {
    ByteState& b = storage_.bytes[i];
    const bool written_now = b.write_epoch == epoch;
    const std::uint16_t writer = b.writer & thread_bits;
    const bool atomic_write = (b.writer & atomic_bit) != 0;
    switch (access) {
      case Access::read:
        if (b.write_epoch < first_epoch_) {
          fail(ErrorKind::shared_uninitialized, self, where,
               "read of shared byte " + std::to_string(i) +
                   ", which no thread of the block has written");
        }
        if (written_now && writer != me && !warp_ordered(self, b.writer, b.write_sequence)) {
          race("read", atomic_write ? "atomic" : "write", b.writer, i);
        }
        if (b.read_epoch != epoch) {
          b.read_epoch = epoch;
          b.reader = me;
          b.reader_warp = my_warp;
          b.read_sequence = sequence;
        } else if (b.reader != me) {
          b.reader = many;
          if (b.reader_warp != my_warp) b.reader_warp = many;
          b.read_sequence = std::max(b.read_sequence, sequence);
        }
        break;
      case Access::write:
      case Access::atomic: {
        const bool atomic = access == Access::atomic;
        if (written_now && writer != me && !(atomic && atomic_write) &&
            !warp_ordered(self, b.writer, b.write_sequence)) {
          race(atomic ? "atomic" : "write", atomic_write ? "atomic" : "write", b.writer, i);
        }
        if (b.read_epoch == epoch && b.reader != me) {
          const bool ordered = b.reader == many ? b.reader_warp == my_warp &&
                                                      warp_ordered_with_all(self, b.read_sequence)
                                                : warp_ordered(self, b.reader, b.read_sequence);
          if (!ordered) race(atomic ? "atomic" : "write", "read", b.reader, i);
        }
        std::uint16_t new_writer = me;
        if (atomic) {
          new_writer = (written_now && atomic_write && writer != me) ? many : me;
          new_writer |= atomic_bit;
        }
        b.write_epoch = epoch;
        b.writer = new_writer;
        b.write_sequence = sequence;
        break;
      }
    }
  }
}

Block& this_block(const char* what) {
  if (t_block == nullptr) {
    throw EmulatorError(ErrorKind::outside_kernel, "", {}, {}, "", 0,
                        std::string(what) + " called outside a kernel");
  }
  return *t_block;
}

}  // namespace

const ThreadInfo& this_thread() {
  return this_block("threadIdx/blockIdx/blockDim/gridDim").current().info;
}

int block_barrier(Barrier kind, int predicate, const Location& where) {
  return this_block("__syncthreads").barrier(kind, predicate, where);
}

std::uint64_t warp_collective(Collective kind, unsigned mask, std::uint64_t value, int lane_arg,
                              int width, const Location& where) {
  return this_block("a warp collective").collective(kind, mask, value, lane_arg, width, where);
}

unsigned active_mask(const Location& where) {
  return this_block("__activemask").activemask(where);
}

void yield_point() {
  this_block("an atomic").yield_point();
}

std::size_t shared_static(const SharedDecl& decl, const Location& where) {
  return this_block("__shared__").shared_static(decl, where);
}

std::size_t dynamic_shared_bytes() {
  return this_block("extern __shared__").dynamic_shared_bytes();
}

std::byte* shared_base() {
  return this_block("__shared__").shared_base();
}

void shared_access(std::size_t offset, std::size_t size, Access access, const Location& where) {
  this_block("__shared__").shared_access(offset, size, access, where);
}

void shared_out_of_bounds(std::size_t index, std::size_t extent, const Location& where) {
  Block& block = this_block("__shared__");
  block.fail(ErrorKind::shared_out_of_bounds, block.current(), where,
             "index " + std::to_string(static_cast<std::ptrdiff_t>(index)) +
                 " into a shared array of " + std::to_string(extent) + " elements");
}

void launch(const char* kernel, Dim3 grid, Dim3 block, std::size_t dynamic_shared,
            const Location& where, ThreadEntry entry, const void* bound_kernel) {
  auto invalid = [&](const std::string& message) {
    throw EmulatorError(ErrorKind::invalid_launch, kernel, {}, {}, where.file_name(), where.line(),
                        message);
  };
  if (t_block != nullptr)
    invalid("a launch from device code (dynamic parallelism) is not emulated");
  const std::uint64_t threads = std::uint64_t(block.x) * block.y * block.z;
  if (block.x == 0 || block.y == 0 || block.z == 0 || threads > 1024 || block.z > 64) {
    invalid("block " + format_dim({block.x, block.y, block.z}) +
            ": a block has 1 to 1024 threads, z at most 64");
  }
  if (grid.x == 0 || grid.y == 0 || grid.z == 0 || grid.x > 0x7fffffffu || grid.y > 65535 ||
      grid.z > 65535) {
    invalid("grid " + format_dim({grid.x, grid.y, grid.z}) +
            ": x in 1..2^31-1, y and z in 1..65535");
  }
  if (dynamic_shared > max_shared_bytes) {
    invalid(std::to_string(dynamic_shared) + " bytes of dynamic shared memory (at most " +
            std::to_string(max_shared_bytes) + ")");
  }
  // Reports name the kernel as written, without its namespace.
  const char* name = kernel;
  for (const char* c = kernel; *c != '\0'; ++c) {
    if (*c == ':') name = c + 1;
  }
  const LaunchState state{
      name, grid, block, dynamic_shared, entry, bound_kernel, current_options()};
  const std::size_t blocks = std::size_t(grid.x) * grid.y * grid.z;

  // Every block below the first failure runs, so the reported error is the lowest failing
  // block's, whatever order TBB runs them in.
  std::mutex mutex;
  std::atomic<std::size_t> first_failure{std::numeric_limits<std::size_t>::max()};
  std::exception_ptr error;
  // Every launch is a phase of the progress line: blocks finished of the grid's, named by the
  // kernel (the long launches of an emulated algorithm are the ones the line shows).
  shadowcts::phase_progress::begin(blocks, "blocks", name);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, blocks, 1),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t b = range.begin(); b != range.end(); ++b) {
                        if (b > first_failure.load(std::memory_order_relaxed)) return;
                        try {
                          Block(state, b).run();
                        } catch (...) {
                          const std::lock_guard lock(mutex);
                          if (b < first_failure.load()) {
                            first_failure = b;
                            error = std::current_exception();
                          }
                        }
                        shadowcts::phase_progress::advance(1);
                      }
                    });
  if (error) std::rethrow_exception(error);
}

}  // namespace detail

// ---------------------------------------------------------------------------------------------
// Runtime API subset

EmuError device_malloc(void** pointer, std::size_t bytes) {
  if (pointer == nullptr) return cudaErrorInvalidValue;
  // Aligned as cudaMalloc's (256 bytes) so alignment assumptions hold here too.
  *pointer = bytes == 0 ? nullptr : std::aligned_alloc(256, detail::align_up(bytes, 256));
  return bytes != 0 && *pointer == nullptr ? cudaErrorMemoryAllocation : cudaSuccess;
}

EmuError device_free(void* pointer) {
  std::free(pointer);
  return cudaSuccess;
}

EmuError device_memcpy(void* destination, const void* source, std::size_t bytes,
                       EmuMemcpyKind kind) {
  if (kind < cudaMemcpyHostToHost || kind > cudaMemcpyDefault) return cudaErrorInvalidValue;
  if (bytes != 0) std::memmove(destination, source, bytes);
  return cudaSuccess;
}

EmuError device_memset(void* destination, int value, std::size_t bytes) {
  if (bytes != 0) std::memset(destination, value, bytes);
  return cudaSuccess;
}

const char* error_name(EmuError status) {
  switch (status) {
    case cudaSuccess:
      return "cudaSuccess";
    case cudaErrorInvalidValue:
      return "cudaErrorInvalidValue";
    case cudaErrorMemoryAllocation:
      return "cudaErrorMemoryAllocation";
  }
  return "cudaErrorUnknown";
}

const char* error_string(EmuError status) {
  switch (status) {
    case cudaSuccess:
      return "no error";
    case cudaErrorInvalidValue:
      return "invalid argument";
    case cudaErrorMemoryAllocation:
      return "out of memory";
  }
  return "unknown error";
}

}  // namespace shadowcts::emu
