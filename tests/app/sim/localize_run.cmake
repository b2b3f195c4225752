# irgs-sim --localize ekf on MAP (the bundled corridor, a lap hugging the central block): the run
# must finish, write both files, and the EKF's RMS error must stay below 0.1 m and below dead
# reckoning's.
file(REMOVE_RECURSE ${WORK})
execute_process(COMMAND ${SIM} --map ${MAP} --out ${WORK} --localize ekf --seed 2
                        --route 15.9,0.775/15.9,-14.55/-1.0,-14.55/-1.0,0.775/2.0,0.775
                RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "irgs-sim --localize ekf failed (${code}): ${out} ${err}")
endif()
foreach(f localization_metrics.json localization.csv)
  if(NOT EXISTS ${WORK}/${f})
    message(FATAL_ERROR "missing output ${f}")
  endif()
endforeach()
file(READ ${WORK}/localization_metrics.json metrics)
string(JSON completed GET "${metrics}" route_completed)
string(JSON ekf GET "${metrics}" estimate rms_position_error_m)
string(JSON dr GET "${metrics}" dead_reckoning rms_position_error_m)
string(JSON nees GET "${metrics}" nees fraction_within_95)
if(NOT completed)
  message(FATAL_ERROR "the route did not complete: ${metrics}")
endif()
# CMake compares integers and decimals as version-like strings: scale to millimetres.
string(REGEX REPLACE "^([0-9]+)\\.([0-9][0-9][0-9]).*$" "\\1\\2" ekf_mm "${ekf}0000")
string(REGEX REPLACE "^([0-9]+)\\.([0-9][0-9][0-9]).*$" "\\1\\2" dr_mm "${dr}0000")
if(ekf_mm GREATER 100 OR NOT dr_mm GREATER ekf_mm)
  message(FATAL_ERROR "EKF RMS ${ekf} m (limit 0.1) vs dead reckoning ${dr} m")
endif()
message(STATUS "EKF RMS ${ekf} m, DR RMS ${dr} m, NEES within 95 % ${nees}")
