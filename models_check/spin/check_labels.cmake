# check_labels.cmake — the SPIN model's steps carry exactly the stealing protocol's site labels of core/site.hpp.
#
#   cmake -DSITE_HPP=core/site.hpp -DPML=models_check/spin/stealing.pml -P check_labels.cmake
#
# From site.hpp: every row of kSiteTable that belongs to Protocol::kStealing (rows that name no protocol
# default to it); the other protocols' rows (greedy rendering's publication, the Chase–Lev deque) are not the
# stealing model's business. From the model, with comments removed: the labels
# declared in its `mtype = { ... }` line, and the labels its steps carry (an access's first argument, or the
# label a merged step prints). The three sets must be equal, and the model must use no other label-shaped
# token (a typo such as O5 fails too).
cmake_minimum_required(VERSION 3.25)
foreach(var SITE_HPP PML)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "check_labels.cmake: -D${var}=... is required")
  endif()
endforeach()

file(READ "${SITE_HPP}" site_text)
string(REPLACE ";" "," site_text "${site_text}")  # a ';' in a row's text would split it as a CMake list
string(REGEX MATCHALL "\\{Site::k[A-Za-z]+, \"[A-Z][0-9]\"[^}]*\\}" rows "${site_text}")
set(site_labels)
foreach(row IN LISTS rows)
  if(row MATCHES "Protocol::k" AND NOT row MATCHES "Protocol::kStealing")
    continue()
  endif()
  string(REGEX MATCH "\"([A-Z][0-9])\"" _ "${row}")
  list(APPEND site_labels "${CMAKE_MATCH_1}")
endforeach()
list(REMOVE_DUPLICATES site_labels)
list(SORT site_labels)
list(LENGTH site_labels n_site)
if(n_site LESS 10)
  message(FATAL_ERROR "check_labels.cmake: found only ${n_site} stealing sites in ${SITE_HPP}: did kSiteTable change shape?")
endif()

file(READ "${PML}" pml_text)
string(REPLACE ";" " " pml_text "${pml_text}")
# Remove /* ... */ comments (they may mention labels in prose).
string(REGEX REPLACE "/\\*([^*]|\\*+[^*/])*\\*+/" "" pml_code "${pml_text}")

# Declared: the mtype line.
string(REGEX MATCH "mtype = \\{[^}]*\\}" mtype_decl "${pml_code}")
if(NOT mtype_decl)
  message(FATAL_ERROR "check_labels.cmake: no `mtype = { ... }` declaration of site labels in ${PML}")
endif()
string(REGEX MATCHALL "[A-Z][0-9]" declared "${mtype_decl}")
list(REMOVE_DUPLICATES declared)
list(SORT declared)

# Carried by steps: every label-shaped token in the code outside the declaration, as a whole word.
string(REPLACE "${mtype_decl}" "" pml_steps "${pml_code}")
string(REGEX REPLACE "[^A-Za-z0-9_]+" ";" tokens "${pml_steps}")
set(used)
foreach(t IN LISTS tokens)
  if(t MATCHES "^[A-Z][0-9]$")
    list(APPEND used "${t}")
  endif()
endforeach()
list(REMOVE_DUPLICATES used)
list(SORT used)

set(ok TRUE)
foreach(pair "declared;the model's mtype declaration" "used;the model's steps")
  list(GET pair 0 var)
  list(GET pair 1 what)
  set(missing ${site_labels})
  list(REMOVE_ITEM missing ${${var}})
  set(extra ${${var}})
  list(REMOVE_ITEM extra ${site_labels})
  if(missing)
    message(SEND_ERROR "site labels of core/site.hpp missing from ${what}: ${missing}")
    set(ok FALSE)
  endif()
  if(extra)
    message(SEND_ERROR "labels in ${what} that core/site.hpp does not have: ${extra}")
    set(ok FALSE)
  endif()
endforeach()
if(NOT ok)
  message(FATAL_ERROR "check_labels.cmake: ${PML} and ${SITE_HPP} disagree on the stealing protocol's site labels")
endif()
string(REPLACE ";" " " shown "${site_labels}")
message(STATUS "SPIN model carries all ${n_site} stealing site labels of core/site.hpp: ${shown}")
