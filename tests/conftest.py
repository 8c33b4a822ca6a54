from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT / "src") not in sys.path:  # running without an installed package
    sys.path.insert(0, str(ROOT / "src"))
