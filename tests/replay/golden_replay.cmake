# Runs vmass-replay on the golden drive and compares the estimate CSV byte for byte.
execute_process(
  COMMAND ${REPLAY} --config ${GOLDEN_DIR}/config.yaml --samples ${GOLDEN_DIR}/samples.csv
          --truth ${GOLDEN_DIR}/truth.csv --out ${OUT}
  RESULT_VARIABLE rc OUTPUT_VARIABLE summary ERROR_VARIABLE errors)
message("${summary}${errors}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "vmass-replay failed with ${rc}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${OUT} ${GOLDEN_DIR}/expected_estimate.csv
  RESULT_VARIABLE differ)
if(NOT differ EQUAL 0)
  execute_process(COMMAND diff ${GOLDEN_DIR}/expected_estimate.csv ${OUT} OUTPUT_VARIABLE d)
  string(SUBSTRING "${d}" 0 3000 d)
  message(FATAL_ERROR "the estimate moved from the golden file (first differences below).\n"
    "If the change is intended, run scripts/update-golden.sh and say why in the commit.\n${d}")
endif()
