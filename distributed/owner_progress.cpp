// owner_progress.cpp — resolving --owner-progress (owner_progress.hpp).
#include "distributed/owner_progress.hpp"

#include <cstdlib>
#include <sstream>

namespace frontsteal::mpi {

ProgressChoice resolve_owner_progress(const std::string& option, double thread_sleep_us, MPI_Comm comm) {
  ProgressChoice c;
  c.thread_sleep_us = thread_sleep_us;
  MPI_Comm node;
  MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
  int node_size = 0, size = 0;
  MPI_Comm_size(node, &node_size);
  MPI_Comm_size(comm, &size);
  MPI_Comm_free(&node);
  c.one_node = node_size == size;
  char version[MPI_MAX_LIBRARY_VERSION_STRING];
  int length = 0;
  MPI_Get_library_version(version, &length);
  c.open_mpi = std::string(version, static_cast<std::size_t>(length)).rfind("Open MPI", 0) == 0;
  if (const char* osc = std::getenv("OMPI_MCA_osc")) c.osc_requested = osc;
  // Only Open MPI's osc/sm is known here to need no target progress (a Get is the origin's own load). MPICH
  // 4.0.2 (ch4:ucx) on one node does: with no progress calls a thief's operations waited for a busy victim to
  // run dry (0 rma steals in 12 skewed frames at 2 ranks; 12 with calls every 50 us).
  // OMPI_MCA_osc is a comma list of components, or "^a,b" for every component but those.
  const bool excluded = !c.osc_requested.empty() && c.osc_requested[0] == '^';
  const bool names_sm = c.osc_requested.find("sm") != std::string::npos;
  const bool sm_allowed = c.osc_requested.empty() || (excluded ? !names_sm : names_sm);
  const bool sm_possible = c.open_mpi && c.one_node && sm_allowed;
  if (option == "auto") {
    c.every_us = sm_possible ? -1 : kAutoProgressEveryUs;
  } else if (option == "off") {
    c.every_us = -1;
  } else {
    c.every_us = std::strtod(option.c_str(), nullptr);  // validated by parse_options()
  }
  return c;
}

std::string ProgressChoice::describe() const {
  std::ostringstream s;
  s << "owner progress calls: ";
  if (every_us < 0) {
    s << "off";
  } else if (every_us == 0) {
    s << "MPI_Iprobe after every item";
  } else {
    s << "MPI_Iprobe at most every " << every_us << " us";
  }
  if (thread_sleep_us == 0) {
    s << "; progress thread: MPI_Iprobe, yielding between calls";
  } else if (thread_sleep_us > 0) {
    s << "; progress thread: MPI_Iprobe, sleeping " << thread_sleep_us << " us between calls";
  }
  s << " (ranks " << (one_node ? "share one node" : "span several nodes") << "; ";
  if (!open_mpi) {
    s << "not Open MPI: its one-sided operations are taken to need the target's progress)";
  } else {
    s << "osc " << (osc_requested.empty() ? "chosen by Open MPI (sm on one node)" : "requested: " + osc_requested)
      << ")";
  }
  return s.str();
}

}  // namespace frontsteal::mpi
