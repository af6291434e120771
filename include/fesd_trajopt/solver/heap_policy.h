#pragma once

#include <cstddef>

namespace fesd {

/// For programs that solve large NLPs (the node, the benches, the tests), not for a library's
/// users to have imposed: keeps blocks up to 32 MiB (glibc's largest threshold) in the process
/// heap instead of fresh memory maps and never trims it on its own, so freed blocks are reused by
/// the next NLP without faulting their pages in again (~12 us per page on this machine's virtual
/// machine). The heap starts with a 64 MiB reserve advised to transparent huge pages: a solve's
/// first touch of its memory faults once per 2 MiB instead of 4 KiB (the showcase's solve: 2950
/// faults -> 1140 in the whole process, 0.095 -> 0.070 s). Call releaseFreeMemory() when a
/// piece of work ends.
void keepLargeAllocationsInTheHeap();

/// Returns the heap's free pages to the system (malloc_trim) once more than `keep_bytes` are
/// free: after a large request the program goes back to about its idle size, while the pages
/// of small requests stay mapped for the next (trimming after every default request cost it
/// about 60 ms of page faults in the next one).
void releaseFreeMemory(std::size_t keep_bytes = std::size_t{256} << 20);

}  // namespace fesd
