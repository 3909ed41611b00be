// table2_report.hpp — the paper's Table 2 beside ours: greedy rendering (render/greedy_renderer.hpp),
// tessellations/s, updates/s and the lag in frames, MEASURED on stand-ins of the paper's models.
//
// Per scene two rows: natural (each surface tessellated once per tessellation frame), and tessellation-bound
// (each surface K times, only the last result published: the tessellators slower than the pusher, as the
// paper's were; --cost-multiplier K|auto|off). Writes table2.{md,csv,json,dat,gp}, table2.png and, with
// OpenGL, a table2-<scene>[-bound]/ folder of frames and colour plates per row.
#pragma once

#include "papers/paper_run.hpp"

namespace frontsteal::papers {

// Exit status: 0; throws render::GraphicsError without OpenGL (the caller exits 3), tess::ModelError for a bad
// scene (2), std::runtime_error when a file cannot be written (1).
int run_table2(PaperRun& run);

}  // namespace frontsteal::papers
