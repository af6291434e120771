#pragma once

namespace fesd {

/// For programs that solve large NLPs (the node, the benches, the tests), not for a library's
/// users to have imposed: keeps large allocations in one process heap instead of fresh memory
/// maps. MUMPS allocates its workspace anew for every factorisation; from a fresh map each time
/// every touched page faults (~12 us each on this machine's virtual machine), which doubled the
/// time of a 26352-variable solve (results.md, "The per-iteration cost"). One arena, no maps
/// below 1 GiB and no automatic trimming: freed blocks are reused by the next factorisation.
/// Call releaseFreeMemory() when a piece of work ends, or the heap keeps its peak size.
void keepLargeAllocationsInTheHeap();

/// Returns the heap's free pages to the system (malloc_trim): after a request, so that a
/// program's memory goes back to about its idle size.
void releaseFreeMemory();

}  // namespace fesd
