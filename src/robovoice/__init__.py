"""robovoice: voice assistance for mobile robots through a function-calling LLM."""
__version__ = "0.1.0"
