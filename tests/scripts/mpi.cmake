# The iteration matrix on MUMPS, in one process and over 2 MPI ranks
# (solver = "mumps", mpirun -np 2 FreeFem++-mpi; method.md §4): each example
# runs with CHOLMOD, with MUMPS in one process and with MUMPS on 2 ranks
# (tests/scripts/mpi-compare.sh). The ranks must write the same CSV bit for
# bit; 2 ranks against 1 process and MUMPS against CHOLMOD must agree to
# 1e-8 of each column's magnitude (measured 2e-12 to 4e-10: round-off, the
# largest in the columns that are differences of energies).
find_program(FREEFEM_MPI_EXECUTABLE FreeFem++-mpi REQUIRED)  # Debian freefem++
find_program(MPIRUN_EXECUTABLE mpirun REQUIRED)             # Debian openmpi-bin
set(NBM_MPI_COMPARE ${CMAKE_CURRENT_SOURCE_DIR}/mpi-compare.sh)
foreach(case
    "bouncing-bar;${EDP}/bouncing-bar.edp;-N;80;-vtkFrames;0"
    "plate-redistributed;${EDP}/bouncing-plate.edp;-T;0.5;-mass;redistributed;-vtkFrames;0;-snapshots;0"
    "drop-3d;${EDP}/drop-3d.edp;-angle;20;-vtkFrames;0;-plot;0"
    "vibrating-table;${EDP}/vibrating-table.edp;-T;0.3;-mass;redistributed;-vtkFrames;0")
  list(POP_FRONT case name script)
  add_test(NAME script.mpi-${name}
    COMMAND bash ${NBM_MPI_COMPARE} ${CMAKE_BINARY_DIR} ${PROJECT_SOURCE_DIR} ${script} mpi-${name} 1e-8 ${case}
    WORKING_DIRECTORY ${NBM_SCRIPT_OUT})
  set_tests_properties(script.mpi-${name} PROPERTIES TIMEOUT 900 LABELS "script;mpi")
endforeach()

# Bad input in parallel (tests/scripts/bad-input/mpi.edp on 2 ranks): rank 1
# passes another matrix, a matrix of the wrong size, or another load. Every
# job must end, never hang, with the error on every rank (or, for the rank
# that waits for one that stopped, its explanation after NBM_MPI_TIMEOUT = 10
# s). Not named bad-input.*: the sanitized run (tests/sanitize.sh) loads its
# plugin into FreeFem++, not FreeFem++-mpi.
set(NBM_MPI_EXPECT ${CMAKE_CURRENT_SOURCE_DIR}/mpi-expect-error.sh)
function(nbm_mpi_bad_input name)  # [pattern...]: none for a case that must succeed
  add_test(NAME mpi-bad-input.${name}
    COMMAND bash ${NBM_MPI_EXPECT} ${CMAKE_BINARY_DIR} ${PROJECT_SOURCE_DIR}
            ${CMAKE_CURRENT_SOURCE_DIR}/bad-input/mpi.edp -case,${name} ${ARGN}
    WORKING_DIRECTORY ${NBM_SCRIPT_OUT})
  set_tests_properties(mpi-bad-input.${name} PROPERTIES TIMEOUT 300 LABELS "bad-input;mpi")
endfunction()
nbm_mpi_bad_input(valid)
nbm_mpi_bad_input(matrix [[differs between MPI ranks \(rank 1 against rank 0\)]]
  [[err code 8 ,  mpirank 0]] [[err code 8 ,  mpirank 1]])
nbm_mpi_bad_input(wrong-size [[M: size 11x11 differs from the size of K, 12x12]]
  [[rank 0 waited 10 s for the other ranks at M \+ beta dt\^2 K]])
nbm_mpi_bad_input(load [[the right-hand side of a solve with .* differs between MPI ranks]]
  [[err code 8 ,  mpirank 0]] [[err code 8 ,  mpirank 1]])

# A restart file written on 2 ranks resumes in one process and on 2 ranks to
# round-off of the uninterrupted run (tests/scripts/mpi-restart.sh: 2 ranks are
# not reproducible bit for bit, even run to run): the plate with the paper's
# NBM and with the massless boundary.
foreach(variant "newmark" "redistributed;-mass;redistributed")
  list(POP_FRONT variant name)
  add_test(NAME script.mpi-restart-${name}
    COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/mpi-restart.sh ${CMAKE_BINARY_DIR} ${PROJECT_SOURCE_DIR} 1e-8 ${variant}
    WORKING_DIRECTORY ${NBM_SCRIPT_OUT})
  set_tests_properties(script.mpi-restart-${name} PROPERTIES TIMEOUT 900 LABELS "script;mpi")
endforeach()
