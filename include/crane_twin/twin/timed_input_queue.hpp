// TimedInputQueue: a real crane's measurements held until the twin's simulated time reaches the
// time they were taken (docs/twin.md "Keeping the crane's time"), ROS-free.
//
// A twin that falls behind real time (a hand-over to full order, a busy machine) catches up by
// running as fast as it can (Pacer's catch-up). Meanwhile the crane's measurements keep coming;
// taken on arrival they would show the twin, in a second of its time, what the crane did in
// five: its drives would run at several times the crane's speed and its load cell would compare
// the crane's present with the twin's past. Held here, each reaches the twin at its own time:
//   t(item) <= now                  due: released at t(item);
//   now < t(item) <= now + horizon  held (the twin will get there);
//   t(item) > now + horizon         released at now: the clocks are apart (another machine's
//                                   clock, a twin that gave up catching up), and a measurement
//                                   the twin would reach only that late is better taken now;
// NaN (no time of its own): released at now. Items leave in arrival order: one held item
// holds those behind it. Beyond `capacity` items the oldest is dropped (and counted).
#pragma once

#include <cmath>
#include <cstddef>
#include <deque>
#include <stdexcept>
#include <utility>

namespace crane_twin {

template <class T>
class TimedInputQueue {
 public:
  /// capacity > 0; throws std::invalid_argument otherwise.
  explicit TimedInputQueue(std::size_t capacity) : capacity_(capacity) {
    if (capacity == 0) throw std::invalid_argument("TimedInputQueue: capacity must be > 0");
  }

  void push(T item) {
    items_.push_back(std::move(item));
    if (items_.size() > capacity_) {
      items_.pop_front();
      ++dropped_;
    }
  }

  /// Calls take(item, t) for every item due at simulated time `now` (the header's rules), in
  /// arrival order; time_of(item) is the simulated time it was taken at (NaN: none).
  template <class TimeOf, class Take>
  void release(double now, double horizon, TimeOf&& time_of, Take&& take) {
    while (!items_.empty()) {
      const double t = time_of(items_.front());
      double at = now;
      if (t <= now) {
        at = t;
      } else if (t <= now + horizon) {
        return;  // held
      }
      T item = std::move(items_.front());
      items_.pop_front();
      take(item, at);
    }
  }

  void clear() { items_.clear(); }
  std::size_t size() const { return items_.size(); }
  /// Items dropped because the queue was full.
  long dropped() const { return dropped_; }

 private:
  std::size_t capacity_;
  std::deque<T> items_;
  long dropped_ = 0;
};

}  // namespace crane_twin
