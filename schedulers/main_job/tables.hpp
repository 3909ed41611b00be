// tables.hpp — the main job's two tables (report::Table): the one the terminal and frontsteal.md show
// (rounded, with verdict texts), and the data table frontsteal.csv and each row of frontsteal.json's results[]
// are made of (full precision, one column per value).
#pragma once

#include "reporting/table.hpp"
#include "schedulers/main_job/analysis.hpp"

namespace frontsteal::main_job {

// The serial loop first, then every scheduler and P, then the cells that could not run.
report::Table shown_table(const Measured& m, const Analysis& a);
// The serial loop first, then every scheduler and P that ran.
report::Table data_table(const Measured& m, const Analysis& a);
// Where the time went: per P and scheduler, its limit-efficiency and every term of its loss account (shares of
// P x T, loss_account.hpp), the work split by the limit's inflation.
report::Table account_table(const Analysis& a);

}  // namespace frontsteal::main_job
