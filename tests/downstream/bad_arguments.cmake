# Calls modelgen_generate with the arguments given in CALL (a ;-list) in script mode: the
# argument checks run before anything that needs a project, so their messages can be tested.
include(${MODELGEN_GENERATE})
cmake_language(EVAL CODE "modelgen_generate(${CALL})")
