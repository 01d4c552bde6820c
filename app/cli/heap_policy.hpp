#pragma once
/// How the process's heap gives memory back to the system.

namespace formsim::app {

/// Keeps freed memory in the heap instead of returning it to the kernel at once: blocks up to
/// 64 MiB come from the heap rather than mappings of their own, and up to 128 MiB of free memory
/// may stay at the heap's top. Each frame's vertex uploads (Mesa reallocates a buffer's storage
/// at every glBufferData), llvmpipe's scenes and the frame buffers allocate and free the same
/// sizes again and again; with glibc's defaults their pages went back to the kernel and were
/// faulted in anew every frame (65 k page faults for 330 frames at 1280x720, 17 k with this
/// policy; a 3840x2160 frame, 33 MB, is above glibc's largest automatic threshold of 32 MiB).
/// No effect outside glibc (nor under a sanitizer's allocator). Call once, first in main.
void ApplyHeapPolicy();

}  // namespace formsim::app
