# `abbe simulate campaign --conventions real` end to end (docs/virtual-machine.md
# §5a): a campaign written as laser software reports it (zeroed, slopes
# removed, relative angles, reflectors 3 mm off) predicts the part after a
# best fit as the absolute campaign does, while its absolute prediction differs.
if(NOT CMAKE_SCRIPT_MODE_FILE)
  add_test(NAME cli_simulate_real_conventions_part
           COMMAND ${CMAKE_COMMAND} -DABBE=$<TARGET_FILE:abbe>
                   -DPROGRAM=${PROJECT_SOURCE_DIR}/nc-samples/thesis-toolpath-1.ngc
                   -DWORK=${CMAKE_CURRENT_BINARY_DIR}/cli_simulate_conventions_work
                   -P ${CMAKE_CURRENT_LIST_FILE})
  set_tests_properties(cli_simulate_real_conventions_part PROPERTIES LABELS cli)
  return()
endif()

file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
function(run)
  execute_process(COMMAND ${ABBE} -q ${ARGN} RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "abbe ${ARGN}: exit code ${rc}\n${err}")
  endif()
endfunction()

run(simulate machine --seed 7 --noise-scale 0 -o ${WORK}/abs)
run(simulate campaign --truth ${WORK}/abs/truth.yaml --noise-scale 0 --conventions real
    --reflector-error 3 -o ${WORK}/real)
# A JSON number (≥ 0, plain or with an exponent below 1e-3) in thousandths.
function(to_milli value out)
  if(value MATCHES "[eE]-")
    set(${out} 0 PARENT_SCOPE)
    return()
  endif()
  string(REGEX MATCH "^([0-9]+)(\\.([0-9]*))?$" m "${value}")
  if(NOT m)
    message(FATAL_ERROR "not a number: ${value}")
  endif()
  set(frac "${CMAKE_MATCH_3}000")
  string(SUBSTRING "${frac}" 0 3 frac)
  math(EXPR v "${CMAKE_MATCH_1} * 1000 + 1${frac} - 1000")
  set(${out} ${v} PARENT_SCOPE)
endfunction()

foreach(c abs real)
  run(predict ${PROGRAM} --machine ${WORK}/${c}/machine.yaml --model ae-arm --align best-fit
      --summary-only --summary-json ${WORK}/${c}.json)
  file(READ ${WORK}/${c}.json json)
  string(JSON ${c}_abs GET "${json}" alignment models 0 absolute rms_d_um)
  string(JSON ${c}_al GET "${json}" alignment models 0 aligned rms_d_um)
endforeach()
message(STATUS "absolute campaign: part rms ${abs_abs} µm, aligned ${abs_al} µm; "
               "real conventions: part rms ${real_abs} µm, aligned ${real_al} µm")
# The aligned rms agree to 0.05 µm (reflectors 3 mm off), the absolute ones
# differ by more than 1 µm (the constants and slopes the conventions removed).
foreach(v abs_abs abs_al real_abs real_al)
  to_milli(${${v}} m_${v})
endforeach()
math(EXPR d_al "${m_real_al} - ${m_abs_al}")
math(EXPR d_abs "${m_real_abs} - ${m_abs_abs}")
if(d_al GREATER 50 OR d_al LESS -50)
  message(FATAL_ERROR "aligned rms differ by ${d_al}/1000 µm (more than 0.05 µm)")
endif()
if(d_abs LESS 1000 AND d_abs GREATER -1000)
  message(FATAL_ERROR "absolute rms differ by only ${d_abs}/1000 µm: the conventions changed nothing?")
endif()
if(m_abs_al LESS 100)
  message(FATAL_ERROR "aligned rms ${abs_al} µm: the part is trivially flat")
endif()
