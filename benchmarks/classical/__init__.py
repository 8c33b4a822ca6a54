"""The classical-planning benchmark of issue 19: IPC-style STRIPS domains and instances.

``generate`` writes seeded problems for each domain, ``harness`` runs
``nowplan plan`` and Fast Downward on them and checks the plans, ``summary``
turns the stored runs into the report; ``benchmarks/classical.py`` is the
command line.  See README.md in this directory.
"""
