# Fits the bundled KR150 excitation run at build time for the firmware-constant tests, quietly
# (modelid's report and its warnings on poorly excited parameters are not the test's business).
# cmake -DMODELID=... -DROBOT=... -DDATA=... -DOUTPUT=... -P fit_estimate.cmake
get_filename_component(output_dir ${OUTPUT} DIRECTORY)
file(MAKE_DIRECTORY ${output_dir})
execute_process(
  COMMAND ${MODELID} fit --robot ${ROBOT} --data ${DATA} --method wls -o ${OUTPUT}
  RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "modelid fit failed (${result}):\n${out}\n${err}")
endif()
