// How much memory this process holds and the machine allows, and byte sizes as users write them.
#pragma once

#include <cstddef>
#include <string>

namespace rad {

/// Resident memory of this process now (Linux /proc/self/statm), 0 if unknown.
size_t resident_bytes();

/// The memory this process may use: the machine's physical memory, or the cgroup's limit when it
/// sets a lower one (containers, Slurm jobs).
size_t machine_memory_bytes();

/// "512M", "8G", "1.5GiB", "2000000": bytes (K, M, G, T are powers of 1024, with or without
/// "iB" or "B"). Throws rad::Error for anything else.
size_t parse_byte_size(const std::string& text);

/// "1.5 GiB", "300 MiB": a size for messages.
std::string format_bytes(double bytes);

}  // namespace rad
