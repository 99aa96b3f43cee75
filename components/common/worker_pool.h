#pragma once

// The one worker pool of the batch tools (the simulation study, the error measurement,
// Where-am-I's seeded runs): indices handed out one at a time to a few threads, results
// written by index so that they do not depend on the threads, and a failure carried back
// to the caller instead of ending the process.

#include <cstddef>
#include <functional>

namespace stickrep {

// What one worker thread does with each index it is handed.
using IndexTask = std::function<void(std::size_t index)>;

// Runs a task for every index in [0, count) on up to `threads` threads (at least one, never
// more than count). `make_task` is called once on each worker thread and returns that
// thread's task, which may hold state of its own (a localizer per thread). The first
// exception thrown by make_task or a task stops the handing out of further indices; once
// every thread has stopped it is rethrown here. `progress`, if set, is called on the
// calling thread about every 100 ms with the number of tasks done, and once with (count,
// count) when all are done.
void ParallelFor(std::size_t count, int threads, const std::function<IndexTask()>& make_task,
                 const std::function<void(std::size_t done, std::size_t count)>& progress = {});

}  // namespace stickrep
