// Runs library work on a given number of threads (0: TBB's default, all cores).
#pragma once

#include <tbb/task_arena.h>

namespace symcompress {

template <typename Body>
auto withThreads(int threads, Body body) {
    if (threads <= 0) return body();
    tbb::task_arena arena(threads);
    return arena.execute(body);
}

}  // namespace symcompress
