// How the tools' processes keep freed memory: a batch of thumbnails parses, uploads and drops a
// scene per item, and the scene parser worker does nothing else. With glibc's defaults the large
// blocks of one scene are mapped and unmapped each time, and the next scene faults its pages in
// again: on the 2-core VM, cold thumbnails spent a third of the parser's time in the kernel, and
// tuned this way the parse fell from 23-26 to 15-17 ms per thumbnail (docs/BENCHMARKS.md). Freed
// memory up to the trim threshold stays in the process for the next scene; RLIMIT_DATA, and so
// --scene-worker-memory-mb, still counts it.
#pragma once

namespace lgh {

// Call once, at the start of main(), before the threads start.
void keepFreedMemoryForReuse();

}  // namespace lgh
