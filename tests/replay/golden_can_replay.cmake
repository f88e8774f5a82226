# Unpacks the CAN-log golden (drive.log, expected_estimate.csv) into WORK, replays the log
# through vmass-replay and compares the estimate CSV byte for byte.
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
execute_process(COMMAND ${CMAKE_COMMAND} -E tar xf ${GOLDEN_DIR}/golden_can.tar.xz
  WORKING_DIRECTORY ${WORK} RESULT_VARIABLE untar)
if(NOT untar EQUAL 0)
  message(FATAL_ERROR "cannot unpack ${GOLDEN_DIR}/golden_can.tar.xz")
endif()
execute_process(
  COMMAND ${REPLAY} --config ${GOLDEN_DIR}/config.yaml --log ${WORK}/drive.log
          --out ${WORK}/estimate.csv
  RESULT_VARIABLE rc OUTPUT_VARIABLE summary ERROR_VARIABLE errors)
message("${summary}${errors}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "vmass-replay failed with ${rc}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${WORK}/estimate.csv
  ${WORK}/expected_estimate.csv RESULT_VARIABLE differ)
if(NOT differ EQUAL 0)
  execute_process(COMMAND diff ${WORK}/expected_estimate.csv ${WORK}/estimate.csv
    OUTPUT_VARIABLE d)
  string(SUBSTRING "${d}" 0 3000 d)
  message(FATAL_ERROR "the CAN-log replay moved from the golden file (first differences "
    "below).\nIf the change is intended, run scripts/update-golden.sh and say why in the "
    "commit.\n${d}")
endif()
