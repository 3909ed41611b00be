// chase_lev_deque.hpp — the baseline scheduler's deque: core/chase_lev_deque.hpp on std::atomic with Lê et al.'s
// orders (ChaseLevOrders). The deque itself, its roles, invariants and orders live in core/ so the model
// checker can run the same source under Relacy (models_check/chaselev_suite.cpp).
#pragma once

#include "core/chase_lev_deque.hpp"

namespace frontsteal::sched {

using frontsteal::StealResult;

template <class T>
using ChaseLevDeque = frontsteal::ChaseLevDeque<T, StdBackend, ChaseLevOrders>;

}  // namespace frontsteal::sched
