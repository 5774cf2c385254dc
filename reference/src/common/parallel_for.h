// Runs fn(i) for i in [0, n) on up to `threads` threads. Work is handed out
// one index at a time, so uneven items (tiles of different difficulty) keep
// every thread busy; the caller makes the result independent of the order.
// An exception thrown by fn (std::bad_alloc) stops the handing out and is
// thrown again in the calling thread once every thread has finished.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <exception>
#include <mutex>
#include <thread>  // needs Threads::Threads
#include <vector>

namespace mrsv {

template <typename Fn>
void parallelFor(uint64_t n, int threads, Fn&& fn) {
  const uint64_t workers = std::min<uint64_t>(n, static_cast<uint64_t>(std::max(threads, 1)));
  if (workers <= 1) {
    for (uint64_t i = 0; i < n; ++i) fn(i);
    return;
  }
  std::atomic<uint64_t> next{0};
  std::exception_ptr failure;
  std::mutex failure_lock;
  auto work = [&] {
    try {
      for (uint64_t i = next++; i < n; i = next++) fn(i);
    } catch (...) {
      std::lock_guard<std::mutex> lock(failure_lock);
      if (!failure) failure = std::current_exception();
      next = n;
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(workers - 1);
  for (uint64_t w = 1; w < workers; ++w) {
    try {
      pool.emplace_back(work);
    } catch (...) {  // no more threads to be had: the ones running finish the work
      break;
    }
  }
  work();
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace mrsv
