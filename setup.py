"""The compiled kernels (the forward engine's, the regression search's loop); everything else is configured in pyproject.toml.

``optional=True``: without a C compiler the install still succeeds and the
forward search runs its pure-Python code (slower).
"""

from setuptools import Extension, setup

setup(
    ext_modules=[
        Extension(
            "nowplan.planning._kernel",
            sources=["src/nowplan/planning/_kernel.c"],
            depends=["src/nowplan/planning/_kernel_heap.h", "src/nowplan/planning/_kernel_gbfs.h", "src/nowplan/planning/_kernel_lama.h",
                     "src/nowplan/planning/_kernel_wastar.h", "src/nowplan/planning/_kernel_axioms.h",
                     "src/nowplan/planning/_kernel_costs.h", "src/nowplan/planning/_kernel_pngs.h"],
            optional=True,
        ),
        Extension(
            "nowplan.planning._kernel_regress",
            sources=["src/nowplan/planning/_kernel_regress.c"],
            depends=["src/nowplan/planning/_kernel_heap.h", "src/nowplan/planning/_kernel_regress_store.h",
                     "src/nowplan/planning/_kernel_regress_nodes.h", "src/nowplan/planning/_kernel_regress_call.h",
                     "src/nowplan/planning/_kernel_regress_task.h"],
            optional=True,
        ),
    ]
)
