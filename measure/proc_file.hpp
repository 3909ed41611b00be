// proc_file.hpp — reading a /proc file whole, safely: "" when it cannot be read, never an exception.
//
// Why a function of its own: a process can end between open() and read(), and read() then fails with ESRCH.
// std::ifstream's buffer turns that into an exception (libstdc++'s basic_filebuf::underflow) that an
// istreambuf_iterator lets through. The noise monitor's children_ticks() reads the stat file of every process
// on the machine, so among a busy machine's short-lived processes it met exactly that: a fresh-clone test run
// (ctest -j2) ended with "basic_filebuf::underflow error reading the file: No such process", exit
// 134. Every /proc/<pid> read of the measurement layer goes through here.
#pragma once

#include <string>

namespace frontsteal::noise {

// The whole text of the file at `path`, or "" when it cannot be opened or read.
std::string read_proc_file(const std::string& path) noexcept;
// The reading half, on a file already open (the test opens, lets the process end, then reads): the text up to
// end of file, or "" when a read fails.
std::string read_open_file(int fd) noexcept;

}  // namespace frontsteal::noise
